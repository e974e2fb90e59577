// SPDX-License-Identifier: MIT
#include "io/log_format.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <string_view>
#include <utility>

#include "core/errors.hpp"
#include "io/log_text_checks.hpp"
#include "io/resample.hpp"
#include "io/time_axis.hpp"
#include "jacobid/yaml/yaml_section.hpp"

namespace jacobid::io {
namespace {

using Section = yaml::YamlSection<InputError>;

constexpr std::size_t kMaxJoints = 64;
// |gain| bounds of a current-to-torque gain, N.m/A (see the gains: check).
constexpr std::pair<double, double> kPlausibleGain{1e-6, 1e6};

// One column reference: a 1-based index, a header name, or (where allowed) null. The rule (docs/log-format.md,
// "Keys"): a plain YAML number is a column number, a quoted scalar is always a name, so `'3'` is the
// column named 3 (it was read as the third column: joints swapped without a word).
ColumnRef column_ref(const Section& s, const YAML::Node& n, const std::string& key, bool nullable, bool header) {
    if (!n.IsDefined() || n.IsNull()) {
        if (!nullable) s.fail(n, key, "null is not allowed here (only for velocities, torques and currents)");
        return {};
    }
    if (!n.IsScalar()) s.fail(n, key, "expected a 1-based column index or a header name");
    const std::string v = n.Scalar();
    const bool quoted = n.Tag() == "!";  // yaml-cpp: "!" for a quoted scalar, "?" for a plain one
    double number = 0.0;
    if (!quoted && parses_as_number(v, number)) {
        if (!(number >= 1.0) || number != std::floor(number) || number > 1e6) {
            s.fail(n, key, fmt::format("column index '{}' must be an integer >= 1 (columns are counted from 1)", v));
        }
        return {static_cast<std::size_t>(number), ""};
    }
    if (!header) {
        s.fail(n, key, quoted && parses_as_number(v, number)
                           ? fmt::format("'{}' is quoted, so a header name, but header: false (write {} without quotes for a column number)", v, v)
                           : fmt::format("'{}' is a header name, but header: false (give a 1-based column index)", v));
    }
    if (v.empty()) s.fail(n, key, "empty column name");
    return {0, v};
}

// A required key written as `null` is there, not missing: say so (it was reported as "missing").
void refuse_null(const Section& s, const std::string& key, const std::string& expected) {
    const YAML::Node n = s.node()[key];
    if (n.IsDefined() && n.IsNull()) s.fail(n, key, fmt::format("null, but {} is required", expected));
}

std::vector<ColumnRef> column_list(Section& s, const std::string& key, bool nullable, bool header, std::size_t size,
                                   const char* of = "columns (one per joint, as positions)") {
    const YAML::Node list = size == 0 ? s.list(key, 1, kMaxJoints, "columns (1-based index or header name)") : s.list(key, size, size, of);
    std::vector<ColumnRef> refs;
    for (std::size_t i = 0; i < list.size(); ++i) refs.push_back(column_ref(s, list[i], fmt::format("{}[{}]", key, i), nullable, header));
    return refs;
}

std::string ms(double seconds) { return fmt::format("{:.4g} ms", 1e3 * seconds); }

// Lines 1,2,3,7 as "1-3, 7"; after 10 ranges, "... (N ranges)".
std::string line_ranges(const std::vector<std::size_t>& lines) {
    constexpr std::size_t kListed = 10;
    std::string out;
    std::size_t ranges = 0;
    for (std::size_t i = 0; i < lines.size();) {
        std::size_t j = i;
        while (j + 1 < lines.size() && lines[j + 1] == lines[j] + 1) ++j;
        if (ranges++ < kListed) out += (out.empty() ? "" : ", ") + (j > i ? fmt::format("{}-{}", lines[i], lines[j]) : std::to_string(lines[i]));
        i = j + 1;
    }
    if (ranges > kListed) out += fmt::format(", ... ({} ranges)", ranges);
    return out;
}

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
    refuse_null(s, "time", "a mapping {column: C, scale: S}");
    {
        Section time = s.child("time");
        refuse_null(time, "column", "the time column (a 1-based index or a header name)");
        if (!time.has("column")) time.fail(time.node(), "column", "missing (required)");
        f.time = column_ref(time, time.get("column"), "column", false, f.header);
        f.time_scale = time.positive("scale", 1.0, "seconds per unit of the time column");
        time.reject_unknown();
    }
    refuse_null(s, "positions", "a list of the joints' position columns");
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
    // `torques: null` alone was "missing"; beside the other key, null is merely not given.
    if (!s.has("currents")) refuse_null(s, "torques", "a list of columns, one per joint (null inside it: a joint without actuator)");
    if (!s.has("torques")) refuse_null(s, "currents", "a list of columns, one per joint (null inside it: a joint without actuator)");
    const bool torques = s.has("torques"), currents = s.has("currents");
    if (torques && currents) s.fail("currents", "give either torques or currents (with gains), not both");
    if (!torques && !currents) s.fail(root, "torques", "missing: give torques, or currents with gains");
    f.currents = currents;
    f.efforts = column_list(s, currents ? "currents" : "torques", true, f.header, joints);
    // Every joint null: every torque 0, and identify gave every parameter exactly 0 with std 0.
    if (std::none_of(f.efforts.begin(), f.efforts.end(), [](const ColumnRef& c) { return c.present(); })) {
        s.fail(currents ? "currents" : "torques", "every joint is null (no actuator), so no effort is read and there is nothing to identify from: "
                                                  "give the column of at least one joint");
    }
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
            // A current-to-torque gain is a torque constant times a gear ratio: from ~1e-3 N.m/A (a small servo's
            // bare motor) to a few 1e3 (a large gearmotor). A gain outside 1e-6 .. 1e6 is a typo or a unit slip,
            // and blamed here, on the key, before it turns a current cell into a torque that is not finite.
            if (std::fabs(v) < kPlausibleGain.first || std::fabs(v) > kPlausibleGain.second) {
                s.fail(g, key, fmt::format("{:g} N.m/A is no current-to-torque gain (expected |gain| within {:g} .. {:g} N.m/A: the motor's torque "
                                           "constant times the gear ratio)", v, kPlausibleGain.first, kPlausibleGain.second));
            }
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
    require_plausible_sample_period(report.median_step, fmt::format("{}: time column {}", source, time_column), format.time_scale, format.source);
    if (settings.max_gap > kMaxGapMedianSteps * report.median_step * (1.0 + 1e-6)) {  // 1e-6: steps read from decimal text
        throw InputError(fmt::format("{}: --max-gap {:g} s is {:.3g} median steps of {}, more than the {:g} median steps ({}) a single step may span: "
                                     "a longer step is always a gap (--on-gap interpolate bridges one of up to --interpolate-max samples and names it, "
                                     "--on-gap split cuts the log there)",
                                     source, settings.max_gap, settings.max_gap / report.median_step, ms(report.median_step), kMaxGapMedianSteps,
                                     ms(kMaxGapMedianSteps * report.median_step)));
    }
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
    if (!skipped.empty()) s += fmt::format(", {} bad rows skipped (lines {}; first: {})", skipped.size(), line_ranges(skipped_lines), skipped.front());
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
