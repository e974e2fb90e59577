// SPDX-License-Identifier: MIT
#include "io/log_format.hpp"

#include <fast_float/fast_float.h>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "core/errors.hpp"
#include "io/increasing_rows.hpp"
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

bool parses_as_number(const std::string& s, double& value) {
    const auto r = fast_float::from_chars(s.data(), s.data() + s.size(), value);
    return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

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

struct SkippedRow {
    std::size_t line;
    std::string message;
};

// --skip-bad-rows: the rows whose times do not fit the longest increasing run (io/increasing_rows.hpp) are
// skipped, each named with the kept row it collides with; `time_column` is 1-based, for the messages.
void keep_increasing_times(RawLog& raw, const std::string& source, std::size_t time_column, std::vector<SkippedRow>& skipped) {
    const std::vector<double> t = raw.table.column(0);
    const std::vector<bool> keep = longest_increasing_times(t);
    std::size_t previous = t.size();  // the last kept row before i (none yet)
    for (std::size_t i = 0; i < t.size(); ++i) {
        if (keep[i]) {
            previous = i;
            continue;
        }
        // Not kept: at or before the previous kept row's time, or else at or after the next kept row's (a
        // longest run leaves no row that fits between its neighbours, so that next kept row exists).
        if (previous < t.size() && !(t[i] > t[previous])) {
            skipped.push_back({raw.lines[i], fmt::format("{}:{}: column {} (time): time {:.10g} s is not after {:.10g} s of line {} (time must increase)",
                                                         source, raw.lines[i], time_column, t[i], t[previous], raw.lines[previous])});
            continue;
        }
        std::size_t next = i + 1;
        while (next < t.size() && !keep[next]) ++next;
        skipped.push_back({raw.lines[i], fmt::format("{}:{}: column {} (time): time {:.10g} s is not before {:.10g} s of line {}, where the "
                                                     "increasing times go on (time must increase)",
                                                     source, raw.lines[i], time_column, t[i], t[next], raw.lines[next])});
    }
    for (std::size_t c = 0; c < raw.table.columns(); ++c) {
        std::vector<double>& column = raw.table.mutable_column(c);
        std::size_t kept = 0;
        for (std::size_t i = 0; i < column.size(); ++i) {
            if (keep[i]) column[kept++] = column[i];
        }
        column.resize(kept);
    }
    std::size_t kept = 0;
    for (std::size_t i = 0; i < raw.lines.size(); ++i) {
        if (keep[i]) raw.lines[kept++] = raw.lines[i];
    }
    raw.lines.resize(kept);
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

RawLog parse_raw_log(const std::string& text, const std::string& source, const LogFormat& format, const LogColumnNames& names,
                     const LogReadSettings& settings, LogReadReport& report) {
    const std::size_t joints = format.joints();
    if (names.q.size() != joints || names.tau.size() != joints || (!format.velocities.empty() && names.qd.size() != joints)) {
        throw InputError(fmt::format("{}: the log format {} has {} joints, the column names {}", source, format.source, joints, names.q.size()));
    }
    report.source = source;
    require_readable_log_text(std::string_view(text).substr(0, text.find('\n')), source);
    TextLines lines(text);
    std::size_t line = 0;
    auto next_line = [&](std::string_view& out) {
        const bool more = lines.next(out);
        line = lines.line();
        if (line == 1) out = without_utf8_bom(out);  // a spreadsheet's encoding marker, not part of the first cell
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
        if (ref.index > 0) {
            // `3` is column 3; a header that names another column '3' makes the intent unclear: refuse.
            const std::string digits = std::to_string(ref.index);
            for (std::size_t c = 0; c < header.size(); ++c) {
                if (header[c] == digits && c + 1 != ref.index) {
                    throw InputError(fmt::format("{}:{}: {}: {} (unquoted) is column number {}, but the header names column {} '{}': quote it ('{}') "
                                                 "for the column of that name, or rename the header",
                                                 source, header_line, key, digits, digits, c + 1, digits, digits));
                }
            }
            return ref.index - 1;
        }
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
            double number = 0.0;
            const std::string number_hint = parses_as_number(ref.name, number)
                                                ? fmt::format(" ('{}' is quoted, so a name; write {} without quotes for a column number)", ref.name, ref.name)
                                                : std::string();
            const std::string delimiter = delimiter_hint(header.size(), header.front(), format.delimiter, format.source);
            if (!delimiter.empty()) {
                throw InputError(fmt::format("{}:{}: {}: no column '{}': the header is one column '{}': {}", source, header_line, key,
                                             printable_cell(ref.name), printable_cell(header.front()), delimiter));
            }
            // A header of numbers is the first data row of a log without one.
            const bool all_numbers = std::all_of(header.begin(), header.end(), [](const std::string& c) {
                double v = 0.0;
                return parses_as_number(c, v);
            });
            throw InputError(fmt::format("{}:{}: {}: no column '{}' in the header{} (columns: {}){}", source, header_line, key, printable_cell(ref.name),
                                         number_hint, describe_columns(header),
                                         all_numbers ? fmt::format("; that line is all numbers: has the log no header? (header: false in {})", format.source)
                                                     : std::string()));
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
            const std::string delimiter = delimiter_hint(width, header.front(), format.delimiter, format.source);
            throw InputError(fmt::format("{}:{}: {}: column {} does not exist, the header has {} columns{}", source, header_line, u.key, u.column + 1,
                                         width, delimiter.empty() ? "" : ": " + delimiter));
        }
    }
    RawLog raw{CsvTable(source, table_names), {}};  // refuses two columns of one name
    std::vector<double> values(uses.size());
    double last_time = 0.0;
    std::size_t last_line = 0;
    std::vector<SkippedRow> skipped;
    auto bad_row = [&](const std::string& reason) {
        const std::string message = fmt::format("{}:{}: {}", source, line, reason);
        if (!settings.skip_bad_rows) throw InputError(message + " (--skip-bad-rows skips such rows and reports them)");
        skipped.push_back({line, message});
    };
    while (next_line(row)) {
        if (trim_cell(row).empty()) {
            if (lines.at_end()) break;  // a final empty line
            bad_row("empty line inside the data");
            continue;
        }
        split(row, format.delimiter, cells);
        if (width == 0) {
            // Strictly, the first data row sets the width. With --skip-bad-rows the most common one does: a
            // misaligned first record made every good row "bad" after it.
            const auto most_common_width = [&] {
                return most_common_cell_count(std::string_view(text).substr(static_cast<std::size_t>(row.data() - text.data())), format.delimiter);
            };
            width = settings.skip_bad_rows ? most_common_width() : cells.size();
            for (const Use& u : uses) {
                if (u.column >= width) {
                    const std::string delimiter = delimiter_hint(width, cells.front(), format.delimiter, format.source);
                    const std::size_t most = most_common_width();
                    const std::string misaligned =
                        most != width ? fmt::format(" (most rows have {}: is this one misaligned? --skip-bad-rows skips it)", most) : std::string();
                    throw InputError(fmt::format("{}:{}: {}: column {} does not exist, the {} has {} columns{}{}", source, line, u.key, u.column + 1,
                                                 settings.skip_bad_rows ? "most common data row" : "first data row", width,
                                                 delimiter.empty() ? "" : ": " + delimiter, misaligned));
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
                // Text in the first data row of a log read without a header is most likely its header.
                const std::string decimal_comma = decimal_comma_hint(cell);
                const bool header_row = !format.header && raw.lines.empty() && skipped.empty() && decimal_comma.empty();
                bad_row(fmt::format("column {} ({}): expected a number, got '{}'{}{}", uses[k].column + 1, uses[k].key, printable_cell(cell),
                                    decimal_comma,
                                    header_row ? fmt::format(" (is line {} a header? header: true or skip_rows in {})", line, format.source) : std::string()));
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
            } else if (ok && beyond_log_range(values[k])) {  // the time too: a corrupt stamp of 1e154 s is no time
                bad_row(fmt::format("column {} ({}): value {} {}", uses[k].column + 1, uses[k].key, values[k], kBeyondLogRange));
                ok = false;
            } else if (ok && k >= 1 && k <= joints && k <= names.q_bounds.size() && names.q_bounds[k - 1] && !names.q_bounds[k - 1]->holds(values[k])) {
                bad_row(fmt::format("column {} ({}): {}", uses[k].column + 1, uses[k].key, names.q_bounds[k - 1]->refusal(values[k])));
                ok = false;
            }
        }
        if (!ok) continue;
        // A zero-filled record (every value read exactly 0, whatever its time) is what a logger
        // writes for a sample it lost; a real robot never measures every joint at exactly 0 rad and 0 N.m (a
        // synthetic log might, at rest at the origin), so only --skip-bad-rows judges it (strictly, its time
        // breaks the order or leaves a gap, named by line).
        if (settings.skip_bad_rows && std::all_of(values.begin() + 1, values.end(), [](double v) { return v == 0.0; })) {
            bad_row("every value but the time is 0 (a zero-filled record, not a sample)");
            continue;
        }
        // With --skip-bad-rows the time order is judged over the whole log once it is read (keep_increasing_times).
        if (!settings.skip_bad_rows && !raw.lines.empty() && !(values[0] > last_time)) {
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
    if (settings.skip_bad_rows) keep_increasing_times(raw, source, uses[0].column + 1, skipped);
    std::stable_sort(skipped.begin(), skipped.end(), [](const SkippedRow& a, const SkippedRow& b) { return a.line < b.line; });
    for (SkippedRow& r : skipped) {
        report.skipped_lines.push_back(r.line);
        report.skipped.push_back(std::move(r.message));
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
