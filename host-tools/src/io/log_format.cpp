// SPDX-License-Identifier: MIT
#include "io/log_format.hpp"

#include <fast_float/fast_float.h>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <string_view>
#include <unordered_map>

#include "core/errors.hpp"
#include "io/resample.hpp"
#include "io/time_axis.hpp"
#include "jacobid/yaml/yaml_section.hpp"

namespace jacobid::io {
namespace {

using Section = yaml::YamlSection<InputError>;

constexpr std::size_t kMaxJoints = 64;

bool parses_as_number(const std::string& s, double& value) {
    const auto r = fast_float::from_chars(s.data(), s.data() + s.size(), value);
    return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

// One column reference: a 1-based index, a header name, or (where allowed) null.
ColumnRef column_ref(const Section& s, const YAML::Node& n, const std::string& key, bool nullable, bool header) {
    if (!n.IsDefined() || n.IsNull()) {
        if (!nullable) s.fail(n, key, "null is not allowed here (only for velocities, torques and currents)");
        return {};
    }
    if (!n.IsScalar()) s.fail(n, key, "expected a 1-based column index or a header name");
    const std::string v = n.Scalar();
    double number = 0.0;
    if (parses_as_number(v, number)) {
        if (!(number >= 1.0) || number != std::floor(number) || number > 1e6) {
            s.fail(n, key, fmt::format("column index '{}' must be an integer >= 1 (columns are counted from 1)", v));
        }
        return {static_cast<std::size_t>(number), ""};
    }
    if (!header) s.fail(n, key, fmt::format("'{}' is a header name, but header: false (give a 1-based column index)", v));
    if (v.empty()) s.fail(n, key, "empty column name");
    return {0, v};
}

std::vector<ColumnRef> column_list(Section& s, const std::string& key, bool nullable, bool header, std::size_t size,
                                   const char* of = "columns (one per joint, as positions)") {
    const YAML::Node list = size == 0 ? s.list(key, 1, kMaxJoints, "columns (1-based index or header name)") : s.list(key, size, size, of);
    std::vector<ColumnRef> refs;
    for (std::size_t i = 0; i < list.size(); ++i) refs.push_back(column_ref(s, list[i], fmt::format("{}[{}]", key, i), nullable, header));
    return refs;
}

void split(std::string_view line, char delimiter, std::vector<std::string_view>& cells) {
    cells.clear();
    for (std::size_t start = 0;;) {
        const std::size_t at = line.find(delimiter, start);
        cells.push_back(trim_cell(line.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start)));
        if (at == std::string_view::npos) break;
        start = at + 1;
    }
}

std::string ms(double seconds) { return fmt::format("{:.4g} ms", 1e3 * seconds); }

}  // namespace

LogFormat parse_log_format(const std::string& yaml_text, const std::string& source) {
    const YAML::Node root = yaml::load<InputError>(yaml_text, source);
    if (!root.IsDefined() || root.IsNull()) throw InputError(fmt::format("{}: empty log format (expected time, positions, torques or currents)", source));
    Section s(source, root, "");
    LogFormat f;
    f.source = source;
    f.header = s.boolean("header", true);
    const std::string delimiter = s.text("delimiter", ",");
    if (delimiter.size() != 1 || std::string_view("0123456789.+-eE\r\n\"").find(delimiter[0]) != std::string_view::npos) {
        s.fail("delimiter", fmt::format("'{}' must be one character that cannot appear in a number, e.g. ',' ';' or \"\\t\"", delimiter));
    }
    f.delimiter = delimiter[0];
    f.skip_rows = static_cast<std::size_t>(s.integer("skip_rows", 0, 0, 1'000'000));
    {
        Section time = s.child("time");
        if (!time.has("column")) time.fail(time.node(), "column", "missing (required)");
        f.time = column_ref(time, time.get("column"), "column", false, f.header);
        f.time_scale = time.positive("scale", 1.0, "seconds per unit of the time column");
        time.reject_unknown();
    }
    if (!s.has("positions")) s.fail(root, "positions", "missing (required): the joints' position columns");
    f.positions = column_list(s, "positions", false, f.header, 0);
    const std::size_t joints = f.positions.size();
    if (s.has("velocities")) {
        f.velocities = column_list(s, "velocities", true, f.header, joints);
    } else {
        s.mark_used("velocities");
    }
    if (s.has("references")) {
        f.references = column_list(s, "references", false, f.header, 2 * joints,
                                   "columns: the joints' reference positions, then their reference velocities");
    } else {
        s.mark_used("references");
    }
    const bool torques = s.has("torques"), currents = s.has("currents");
    if (torques && currents) s.fail("currents", "give either torques or currents (with gains), not both");
    if (!torques && !currents) s.fail(root, "torques", "missing: give torques, or currents with gains");
    f.currents = currents;
    f.efforts = column_list(s, currents ? "currents" : "torques", true, f.header, joints);
    s.mark_used(currents ? "torques" : "currents");
    if (currents) {
        if (!s.has("gains")) s.fail(root, "gains", "missing: currents need gains (N.m/A, tau = gain * current; null for a joint without actuator)");
        const YAML::Node gains = s.list("gains", joints, joints, "gains (one per joint, N.m/A, as currents)");
        for (std::size_t j = 0; j < joints; ++j) {
            const std::string key = fmt::format("gains[{}]", j);
            const YAML::Node g = gains[j];
            if (!f.efforts[j].present()) {
                if (!g.IsNull()) s.fail(g, key, "currents[" + std::to_string(j) + "] is null (no actuator): its gain must be null too");
                f.gains.push_back(0.0);
                continue;
            }
            if (g.IsNull()) s.fail(g, key, "null gain for a logged current (give the current-to-torque gain in N.m/A)");
            const double v = s.number_element(g, key, "N.m/A");
            if (v == 0.0) s.fail(g, key, "a gain of 0 discards the current: use null in currents for a joint without actuator");
            f.gains.push_back(v);
        }
    } else {
        if (s.has("gains")) s.fail("gains", "gains scale currents: use them with currents, not torques");
        s.mark_used("gains");
        f.gains.assign(joints, 1.0);
    }
    s.reject_unknown();
    return f;
}

LogFormat load_log_format(const std::string& path) { return parse_log_format(read_text_file(path, "log format"), path); }

LogColumnNames LogColumnNames::numbered(std::size_t joints, const std::string& time) {
    LogColumnNames n;
    n.time = time;
    for (std::size_t j = 1; j <= joints; ++j) {
        n.q.push_back(fmt::format("q{}", j));
        n.qd.push_back(fmt::format("qd{}", j));
        n.tau.push_back(fmt::format("tau{}", j));
    }
    return n;
}

RawLog parse_raw_log(const std::string& text, const std::string& source, const LogFormat& format, const LogColumnNames& names,
                     const LogReadSettings& settings, LogReadReport& report) {
    const std::size_t joints = format.joints();
    if (names.q.size() != joints || names.tau.size() != joints || (!format.velocities.empty() && names.qd.size() != joints)) {
        throw InputError(fmt::format("{}: the log format {} has {} joints, the column names {}", source, format.source, joints, names.q.size()));
    }
    report.source = source;
    TextLines lines(text);
    std::size_t line = 0;
    auto next_line = [&](std::string_view& out) {
        const bool more = lines.next(out);
        line = lines.line();
        return more;
    };
    std::string_view row;
    for (std::size_t i = 0; i < format.skip_rows; ++i) {
        if (!next_line(row)) throw InputError(fmt::format("{}: {} lines, fewer than skip_rows: {} of {}", source, line, format.skip_rows, format.source));
    }
    std::vector<std::string_view> cells;
    std::vector<std::string> header;
    std::size_t width = 0;
    if (format.header) {
        if (!next_line(row) || trim_cell(row).empty()) throw InputError(fmt::format("{}:{}: expected the header row (header: true in {})", source, line + 1, format.source));
        split(row, format.delimiter, cells);
        for (auto c : cells) {
            if (c.size() >= 2 && c.front() == '"' && c.back() == '"') c = c.substr(1, c.size() - 2);
            header.emplace_back(c);
        }
        width = header.size();
    }
    const std::size_t header_line = line;
    // Resolves a reference to a 0-based column; the width check waits for the first data row without a header.
    auto resolve = [&](const ColumnRef& ref, const std::string& key) -> std::size_t {
        if (ref.index > 0) return ref.index - 1;
        std::size_t found = header.size();
        for (std::size_t c = 0; c < header.size(); ++c) {
            if (header[c] != ref.name) continue;
            if (found != header.size()) {
                throw InputError(fmt::format("{}:{}: {}: column name '{}' appears twice in the header (columns {} and {})", source, header_line, key,
                                             printable_cell(ref.name), found + 1, c + 1));
            }
            found = c;
        }
        if (found == header.size()) {
            throw InputError(fmt::format("{}:{}: {}: no column '{}' in the header (columns: {})", source, header_line, key, printable_cell(ref.name),
                                         describe_columns(header)));
        }
        return found;
    };
    struct Use {
        std::size_t column;    // 0-based in the raw log
        std::string key;       // the log format's key, for messages
        double gain;
    };
    std::vector<Use> uses;  // time, q.., qd.. (logged), tau.. (logged), in table order
    std::vector<std::string> table_names{names.time};
    uses.push_back({resolve(format.time, "time.column"), "time", format.time_scale});
    for (std::size_t j = 0; j < joints; ++j) {
        uses.push_back({resolve(format.positions[j], fmt::format("positions[{}]", j)), fmt::format("positions[{}]", j), 1.0});
        table_names.push_back(names.q[j]);
    }
    for (std::size_t j = 0; j < format.velocities.size(); ++j) {
        if (!format.velocities[j].present()) continue;
        uses.push_back({resolve(format.velocities[j], fmt::format("velocities[{}]", j)), fmt::format("velocities[{}]", j), 1.0});
        table_names.push_back(names.qd[j]);
    }
    for (std::size_t k = 0; k < format.references.size(); ++k) {
        const std::string key = fmt::format("references[{}]", k);
        uses.push_back({resolve(format.references[k], key), key, 1.0});
        table_names.push_back(fmt::format("{}{}", k < joints ? "q_ref" : "qd_ref", k % joints + 1));
    }
    const char* effort = format.currents ? "currents" : "torques";
    std::vector<std::size_t> zero_torque;  // table columns of joints without actuator
    for (std::size_t j = 0; j < joints; ++j) {
        if (format.efforts[j].present()) {
            uses.push_back({resolve(format.efforts[j], fmt::format("{}[{}]", effort, j)), fmt::format("{}[{}]", effort, j), format.gains[j]});
        } else {
            zero_torque.push_back(table_names.size());
        }
        table_names.push_back(names.tau[j]);
    }
    // Each signal from its own raw column: `positions: [t, q2]` read the time as joint 1's position.
    std::unordered_map<std::size_t, const Use*> reader_of;
    for (const Use& u : uses) {
        const auto [it, fresh] = reader_of.emplace(u.column, &u);
        if (!fresh) {
            throw InputError(fmt::format("{}: '{}' reads raw column {}, which '{}' also reads; give each signal its own column", source, u.key,
                                         u.column + 1, it->second->key));
        }
    }
    for (const Use& u : uses) {
        if (format.header && u.column >= width) {
            throw InputError(fmt::format("{}:{}: {}: column {} does not exist, the header has {} columns", source, header_line, u.key, u.column + 1, width));
        }
    }
    RawLog raw{CsvTable(source, table_names), {}};  // refuses two columns of one name
    std::vector<double> values(uses.size());
    double last_time = 0.0;
    std::size_t last_line = 0;
    auto bad_row = [&](const std::string& reason) {
        const std::string message = fmt::format("{}:{}: {}", source, line, reason);
        if (!settings.skip_bad_rows) throw InputError(message + " (--skip-bad-rows skips such rows and reports them)");
        report.skipped.push_back(message);
    };
    while (next_line(row)) {
        if (trim_cell(row).empty()) {
            if (lines.at_end()) break;  // a final empty line
            bad_row("empty line inside the data");
            continue;
        }
        split(row, format.delimiter, cells);
        if (width == 0) {
            width = cells.size();
            for (const Use& u : uses) {
                if (u.column >= width) {
                    throw InputError(fmt::format("{}:{}: {}: column {} does not exist, the first data row has {} columns", source, line, u.key,
                                                 u.column + 1, width));
                }
            }
        }
        if (cells.size() != width) {
            bad_row(fmt::format("expected {} columns, found {}", width, cells.size()));
            continue;
        }
        bool ok = true;
        for (std::size_t k = 0; k < uses.size() && ok; ++k) {
            const std::string_view cell = cells[uses[k].column];
            double v = 0.0;
            const auto r = fast_float::from_chars(cell.data(), cell.data() + cell.size(), v);
            if (r.ec != std::errc() || r.ptr != cell.data() + cell.size() || cell.empty()) {
                bad_row(fmt::format("column {} ({}): expected a number, got '{}'", uses[k].column + 1, uses[k].key, printable_cell(cell)));
                ok = false;
            } else if (!std::isfinite(v)) {
                bad_row(fmt::format("column {} ({}): value '{}' is not finite (NaN or Inf)", uses[k].column + 1, uses[k].key, printable_cell(cell)));
                ok = false;
            }
            values[k] = v * uses[k].gain;
            if (ok && !std::isfinite(values[k])) {
                bad_row(fmt::format("column {} ({}): {} times the gain or scale {} is not finite", uses[k].column + 1, uses[k].key, printable_cell(cell),
                                    uses[k].gain));
                ok = false;
            } else if (ok && k > 0 && beyond_log_range(values[k])) {  // the time has checks of its own (span, steps)
                bad_row(fmt::format("column {} ({}): value {} {}", uses[k].column + 1, uses[k].key, values[k], kBeyondLogRange));
                ok = false;
            } else if (ok && k >= 1 && k <= joints && k <= names.q_bounds.size() && names.q_bounds[k - 1] && !names.q_bounds[k - 1]->holds(values[k])) {
                bad_row(fmt::format("column {} ({}): {}", uses[k].column + 1, uses[k].key, names.q_bounds[k - 1]->refusal(values[k])));
                ok = false;
            }
        }
        if (!ok) continue;
        if (!raw.lines.empty() && !(values[0] > last_time)) {
            bad_row(fmt::format("column {} (time): time {:.10g} s is not after {:.10g} s of line {} (time must increase)", uses[0].column + 1,
                                values[0], last_time, last_line));
            continue;
        }
        last_time = values[0];
        last_line = line;
        std::size_t k = 0;
        for (std::size_t c = 0; c < table_names.size(); ++c) {
            const bool zero = std::find(zero_torque.begin(), zero_torque.end(), c) != zero_torque.end();
            raw.table.mutable_column(c).push_back(zero ? 0.0 : values[k++]);
        }
        raw.lines.push_back(line);
    }
    report.lines = line;
    report.rows = raw.lines.size();
    return raw;
}

std::vector<CsvTable> parse_formatted_log_segments(const std::string& text, const std::string& source, const LogFormat& format,
                                                   const LogColumnNames& names, const LogReadSettings& settings, LogReadReport& report) {
    const RawLog raw = parse_raw_log(text, source, format, names, settings, report);
    const std::vector<double>& t = raw.table.column(0);
    if (t.size() < 2) throw InputError(fmt::format("{}: {} data row(s), need at least 2", source, t.size()));
    // The median step is the nominal period (robust to the UR10e's 10/12 ms alternation and rare steps);
    // a step farther than half of it from it is irregular and named, a step beyond max_gap is a gap.
    report.median_step = median_step(t);
    if (!std::isfinite(t.back() - t.front())) throw InputError(fmt::format("{}: the time span {} s to {} s is not finite", source, t.front(), t.back()));
    const std::string time_column = format.time.index > 0 ? std::to_string(format.time.index) : "'" + printable_cell(format.time.name) + "'";
    require_plausible_sample_period(report.median_step, fmt::format("{}: time column {} (time.column of {}, scale {:g} s per unit)", source,
                                                                    time_column, format.source, format.time_scale));
    const double max_gap = settings.max_gap > 0.0 ? settings.max_gap : 3.0 * report.median_step;
    const UniformGrid grid = uniform_grid(t, max_gap, settings.period);
    // A grid far denser than the log (an imposed period, or steps of 1e-300 s) would exhaust memory. With
    // split the whole span is never put on one grid (each segment is checked below), only its period is used.
    const bool split = settings.on_gap == GapPolicy::Split;
    const auto too_dense = [](std::size_t samples, std::size_t rows) {
        return !(static_cast<double>(samples) <= 100.0 * static_cast<double>(rows) + 1e6);
    };
    if (!(grid.period > 0.0) || grid.samples == 0 || (!split && too_dense(grid.samples, t.size()))) {
        throw InputError(fmt::format("{}: a uniform grid every {:.6g} s over {:.6g} s would need {:.3g} samples for {} rows", source, grid.period,
                                     t.back() - t.front(), (t.back() - t.front()) / grid.period, t.size()));
    }
    std::vector<std::size_t> cuts{0};  // raw row indices where a segment starts (split only), then the end
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        const double step = t[i + 1] - t[i];
        const std::size_t at = raw.lines[i + 1];
        if (step > max_gap) {
            const double missing = std::max(0.0, std::round(step / grid.period) - 1.0);
            if (settings.on_gap == GapPolicy::Error) {
                throw InputError(fmt::format("{}:{}: time step {} after line {} is a gap (longer than --max-gap {}); --on-gap interpolate "
                                             "fills gaps of up to --interpolate-max samples, --on-gap split cuts the log there",
                                             source, at, ms(step), raw.lines[i], ms(max_gap)));
            }
            if (settings.on_gap == GapPolicy::Interpolate && missing > static_cast<double>(settings.interpolate_max)) {
                throw InputError(fmt::format("{}:{}: time step {} after line {} is a gap of {} samples, more than --interpolate-max {}", source, at,
                                             ms(step), raw.lines[i], missing, settings.interpolate_max));
            }
            if (split) cuts.push_back(i + 1);
            report.gap_lines.push_back(at);
            report.gap_steps.push_back(step);
        } else if (std::abs(step - report.median_step) > 0.5 * report.median_step) {
            report.irregular_lines.push_back(at);
            report.irregular_steps.push_back(step);
        }
    }
    cuts.push_back(t.size());
    report.split = split;
    report.grid_period = grid.period;
    report.grid_start = grid.start;
    report.samples = 0;
    const bool several = cuts.size() > 2;
    std::vector<CsvTable> tables;
    for (std::size_t s = 0; s + 1 < cuts.size(); ++s) {
        const auto b = static_cast<std::ptrdiff_t>(cuts[s]), e = static_cast<std::ptrdiff_t>(cuts[s + 1]);
        LogSegment seg;
        seg.first_line = raw.lines[cuts[s]];
        seg.last_line = raw.lines[cuts[s + 1] - 1];
        seg.rows = cuts[s + 1] - cuts[s];
        seg.start = t[cuts[s]];
        seg.duration = t[cuts[s + 1] - 1] - seg.start;
        // Without split the one segment is the whole log on the grid above, exactly as before segments existed.
        const std::vector<double> ts(t.begin() + b, t.begin() + e);
        UniformGrid g = several ? uniform_grid(ts, max_gap, grid.period) : grid;
        if (seg.rows == 1) g = {seg.start, grid.period, 1};
        if (too_dense(g.samples, seg.rows)) {
            throw InputError(fmt::format("{}: lines {}-{}: a uniform grid every {:.6g} s over {:.6g} s would need {} samples for {} rows", source,
                                         seg.first_line, seg.last_line, g.period, seg.duration, g.samples, seg.rows));
        }
        seg.samples = g.samples;
        const std::string name = several ? fmt::format("{} (lines {}-{})", source, seg.first_line, seg.last_line) : source;
        // Every channel onto the uniform grid by a natural cubic spline through the samples at their own times
        // (docs/method.md, "Non-uniform sampling", measured against exact weights for the actual times).
        CsvTable out(name, raw.table.header());
        std::vector<double>& time = out.mutable_column(0);
        time.resize(g.samples);
        for (std::size_t k = 0; k < g.samples; ++k) time[k] = g.start + static_cast<double>(k) * g.period;
        for (std::size_t c = 1; c < raw.table.columns(); ++c) {
            const std::vector<double> x(raw.table.column(c).begin() + b, raw.table.column(c).begin() + e);
            out.mutable_column(c) = seg.rows == 1 ? x : resample(ts, x, g);
            // Steps many orders of magnitude apart (1e-300 s next to 1 s) overflow the spline: say so.
            for (const double v : out.mutable_column(c)) {
                if (!std::isfinite(v)) throw InputError(fmt::format("{}: column '{}' is not finite after resampling (time steps of very different sizes?)", name, out.header()[c]));
            }
        }
        report.samples += g.samples;
        report.segments.push_back(seg);
        tables.push_back(std::move(out));
    }
    return tables;
}

CsvTable parse_formatted_log(const std::string& text, const std::string& source, const LogFormat& format, const LogColumnNames& names,
                             const LogReadSettings& settings, LogReadReport& report) {
    std::vector<CsvTable> tables = parse_formatted_log_segments(text, source, format, names, settings, report);
    if (tables.size() > 1) {
        throw InputError(fmt::format("{}:{}: time step {} is a gap and --on-gap split cuts the log into {} segments, but this reader takes one table",
                                     source, report.gap_lines.front(), ms(report.gap_steps.front()), tables.size()));
    }
    return std::move(tables.front());
}

CsvTable read_formatted_log(const std::string& path, const LogFormat& format, const LogColumnNames& names, const LogReadSettings& settings,
                            LogReadReport& report) {
    return parse_formatted_log(read_text_file(path, "file"), path, format, names, settings, report);
}

std::vector<CsvTable> read_formatted_log_segments(const std::string& path, const LogFormat& format, const LogColumnNames& names,
                                                  const LogReadSettings& settings, LogReadReport& report) {
    return parse_formatted_log_segments(read_text_file(path, "file"), path, format, names, settings, report);
}

std::string LogSegment::describe() const { return fmt::format("lines {}-{}: {:.4g} s, {} samples", first_line, last_line, duration, samples); }

std::string LogReadReport::summary() const {
    std::string s = fmt::format("{}: {} rows read", source, rows);
    if (!skipped.empty()) s += fmt::format(", {} bad rows skipped (first: {})", skipped.size(), skipped.front());
    s += fmt::format("; median step {}; ", ms(median_step));
    if (irregular_lines.empty()) {
        s += "no irregular steps";
    } else {
        s += fmt::format("{} irregular step{} (first at line {}: {})", irregular_lines.size(), irregular_lines.size() == 1 ? "" : "s",
                         irregular_lines.front(), ms(irregular_steps.front()));
    }
    if (!gap_lines.empty()) {
        s += fmt::format("; {} gap{} {} (first at line {}: {})", gap_lines.size(), gap_lines.size() == 1 ? "" : "s",
                         split ? fmt::format("split the log into {} segments", segments.size()) : std::string("interpolated"), gap_lines.front(),
                         ms(gap_steps.front()));
    }
    s += fmt::format("; resampled (cubic spline) onto {} samples every {}", samples, ms(grid_period));
    if (segments.size() > 1) s += fmt::format(" in all, each segment on its own grid");
    return s;
}

}  // namespace jacobid::io
