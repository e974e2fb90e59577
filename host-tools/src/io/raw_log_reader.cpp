// SPDX-License-Identifier: MIT
// parse_raw_log (log_format.hpp): a robot's own log text read as a log format describes it, in its stages:
// the header row, each signal's raw column resolved (by number or name, every one checked), the data rows
// parsed and checked cell by cell, and with --skip-bad-rows the rows out of time order left out. Every
// refusal names the file, the line, the column and the format's key.
#include <fast_float/fast_float.h>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <string_view>
#include <unordered_map>

#include "core/errors.hpp"
#include "io/increasing_rows.hpp"
#include "io/log_format.hpp"
#include "io/log_text_checks.hpp"

namespace jacobid::io {
namespace {

void split(std::string_view line, char delimiter, std::vector<std::string_view>& cells) {
    cells.clear();
    for (std::size_t start = 0;;) {
        const std::size_t at = line.find(delimiter, start);
        cells.push_back(trim_cell(line.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start)));
        if (at == std::string_view::npos) break;
        start = at + 1;
    }
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

// The log's lines one by one, with the line number for messages; the first line loses a UTF-8 byte order
// mark (a spreadsheet's encoding marker, not part of the first cell).
class NumberedLines {
public:
    explicit NumberedLines(const std::string& text) : lines_(text) {}
    bool next(std::string_view& out) {
        const bool more = lines_.next(out);
        line_ = lines_.line();
        if (line_ == 1) out = without_utf8_bom(out);
        return more;
    }
    std::size_t line() const { return line_; }
    bool at_end() const { return lines_.at_end(); }

private:
    TextLines lines_;
    std::size_t line_ = 0;
};

struct HeaderRow {
    std::vector<std::string> cells;  // empty without a header
    std::size_t line = 0;            // the header's line, or the last line skipped before the data
};

HeaderRow read_header(NumberedLines& lines, const std::string& source, const LogFormat& format) {
    std::string_view row;
    for (std::size_t i = 0; i < format.skip_rows; ++i) {
        if (!lines.next(row)) throw InputError(fmt::format("{}: {} lines, fewer than skip_rows: {} of {}", source, lines.line(), format.skip_rows, format.source));
    }
    HeaderRow header;
    if (format.header) {
        if (!lines.next(row) || trim_cell(row).empty()) {
            throw InputError(fmt::format("{}:{}: expected the header row (header: true in {})", source, lines.line() + 1, format.source));
        }
        std::vector<std::string_view> cells;
        split(row, format.delimiter, cells);
        for (auto c : cells) {
            if (c.size() >= 2 && c.front() == '"' && c.back() == '"') c = c.substr(1, c.size() - 2);
            header.cells.emplace_back(c);
        }
    }
    header.line = lines.line();
    return header;
}

// `ref.name` is in no header cell: say what the header holds and what the reference probably meant.
[[noreturn]] void refuse_missing_name(const ColumnRef& ref, const std::string& key, const HeaderRow& header, const std::string& source,
                                      const LogFormat& format) {
    const std::vector<std::string>& cells = header.cells;
    double number = 0.0;
    const std::string number_hint = parses_as_number(ref.name, number)
                                        ? fmt::format(" ('{}' is quoted, so a name; write {} without quotes for a column number)", ref.name, ref.name)
                                        : std::string();
    const std::string delimiter = delimiter_hint(cells.size(), cells.front(), format.delimiter, format.source);
    if (!delimiter.empty()) {
        throw InputError(fmt::format("{}:{}: {}: no column '{}': the header is one column '{}': {}", source, header.line, key, printable_cell(ref.name),
                                     printable_cell(cells.front()), delimiter));
    }
    // A header of numbers is the first data row of a log without one.
    const bool all_numbers = std::all_of(cells.begin(), cells.end(), [](const std::string& c) {
        double v = 0.0;
        return parses_as_number(c, v);
    });
    throw InputError(fmt::format("{}:{}: {}: no column '{}' in the header{} (columns: {}){}", source, header.line, key, printable_cell(ref.name), number_hint,
                                 describe_columns(cells),
                                 all_numbers ? fmt::format("; that line is all numbers: has the log no header? (header: false in {})", format.source)
                                             : std::string()));
}

// A reference as a 0-based column; the width check waits for the first data row without a header.
std::size_t resolve_column(const ColumnRef& ref, const std::string& key, const HeaderRow& header, const std::string& source, const LogFormat& format) {
    const std::vector<std::string>& cells = header.cells;
    if (ref.index > 0) {
        // `3` is column 3; a header that names another column '3' makes the intent unclear: refuse.
        const std::string digits = std::to_string(ref.index);
        for (std::size_t c = 0; c < cells.size(); ++c) {
            if (cells[c] == digits && c + 1 != ref.index) {
                throw InputError(fmt::format("{}:{}: {}: {} (unquoted) is column number {}, but the header names column {} '{}': quote it ('{}') "
                                             "for the column of that name, or rename the header",
                                             source, header.line, key, digits, digits, c + 1, digits, digits));
            }
        }
        return ref.index - 1;
    }
    std::size_t found = cells.size();
    for (std::size_t c = 0; c < cells.size(); ++c) {
        if (cells[c] != ref.name) continue;
        if (found != cells.size()) {
            throw InputError(fmt::format("{}:{}: {}: column name '{}' appears twice in the header (columns {} and {})", source, header.line, key,
                                         printable_cell(ref.name), found + 1, c + 1));
        }
        found = c;
    }
    if (found == cells.size()) refuse_missing_name(ref, key, header, source, format);
    return found;
}

// Which raw column each table column comes from: time, q.., qd.. (logged), references, tau.. (logged), in
// table order; joints without an actuator get a torque column of zeros.
struct ColumnPlan {
    struct Use {
        std::size_t column;  // 0-based in the raw log
        std::string key;     // the log format's key, for messages
        double gain;
    };
    std::vector<Use> uses;
    std::vector<std::string> table_names;
    std::vector<std::size_t> zero_torque;  // table columns of joints without actuator
};

ColumnPlan plan_columns(const LogFormat& format, const LogColumnNames& names, const HeaderRow& header, const std::string& source) {
    const std::size_t joints = format.joints();
    ColumnPlan plan;
    const auto use = [&](const ColumnRef& ref, const std::string& key, double gain) {
        plan.uses.push_back({resolve_column(ref, key, header, source, format), key, gain});
    };
    plan.table_names.push_back(names.time);
    use(format.time, "time.column", format.time_scale);
    plan.uses.back().key = "time";
    for (std::size_t j = 0; j < joints; ++j) {
        use(format.positions[j], fmt::format("positions[{}]", j), 1.0);
        plan.table_names.push_back(names.q[j]);
    }
    for (std::size_t j = 0; j < format.velocities.size(); ++j) {
        if (!format.velocities[j].present()) continue;
        use(format.velocities[j], fmt::format("velocities[{}]", j), 1.0);
        plan.table_names.push_back(names.qd[j]);
    }
    for (std::size_t k = 0; k < format.references.size(); ++k) {
        use(format.references[k], fmt::format("references[{}]", k), 1.0);
        plan.table_names.push_back(fmt::format("{}{}", k < joints ? "q_ref" : "qd_ref", k % joints + 1));
    }
    const char* effort = format.currents ? "currents" : "torques";
    for (std::size_t j = 0; j < joints; ++j) {
        if (format.efforts[j].present()) {
            use(format.efforts[j], fmt::format("{}[{}]", effort, j), format.gains[j]);
        } else {
            plan.zero_torque.push_back(plan.table_names.size());
        }
        plan.table_names.push_back(names.tau[j]);
    }
    // Each signal from its own raw column: `positions: [t, q2]` read the time as joint 1's position.
    std::unordered_map<std::size_t, const ColumnPlan::Use*> reader_of;
    for (const ColumnPlan::Use& u : plan.uses) {
        const auto [it, fresh] = reader_of.emplace(u.column, &u);
        if (!fresh) {
            throw InputError(fmt::format("{}: '{}' reads raw column {}, which '{}' also reads; give each signal its own column", source, u.key, u.column + 1,
                                         it->second->key));
        }
    }
    return plan;
}

// Every used column within `width` columns; `what` names the row that set the width.
void require_columns_exist(const ColumnPlan& plan, std::size_t width, std::string_view first_cell, std::size_t line, const std::string& what,
                           const std::string& misaligned, const std::string& source, const LogFormat& format) {
    for (const ColumnPlan::Use& u : plan.uses) {
        if (u.column < width) continue;
        const std::string delimiter = delimiter_hint(width, first_cell, format.delimiter, format.source);
        throw InputError(fmt::format("{}:{}: {}: column {} does not exist, the {} has {} columns{}{}", source, line, u.key, u.column + 1, what, width,
                                     delimiter.empty() ? "" : ": " + delimiter, misaligned));
    }
}

// One data row's used cells as numbers, each checked (a number, finite, finite times its gain, within the
// log range, a position within its joint's bounds); the first refusal's reason, or "" when the row is good.
// `maybe_header`: this may be a header the format does not expect (the first data row of a log read without one).
std::string read_row_values(const std::vector<std::string_view>& cells, const ColumnPlan& plan, const LogColumnNames& names, std::size_t joints,
                            bool maybe_header, std::size_t line, const LogFormat& format, std::vector<double>& values) {
    for (std::size_t k = 0; k < plan.uses.size(); ++k) {
        const ColumnPlan::Use& u = plan.uses[k];
        const std::string_view cell = cells[u.column];
        double v = 0.0;
        const auto r = fast_float::from_chars(cell.data(), cell.data() + cell.size(), v);
        if (r.ec != std::errc() || r.ptr != cell.data() + cell.size() || cell.empty()) {
            // Text in the first data row of a log read without a header is most likely its header.
            const std::string decimal_comma = decimal_comma_hint(cell);
            const bool header_row = maybe_header && decimal_comma.empty();
            return fmt::format("column {} ({}): expected a number, got '{}'{}{}", u.column + 1, u.key, printable_cell(cell), decimal_comma,
                               header_row ? fmt::format(" (is line {} a header? header: true or skip_rows in {})", line, format.source) : std::string());
        }
        if (!std::isfinite(v)) return fmt::format("column {} ({}): value '{}' is not finite (NaN or Inf)", u.column + 1, u.key, printable_cell(cell));
        values[k] = v * u.gain;
        if (!std::isfinite(values[k])) {
            return fmt::format("column {} ({}): {} times the gain or scale {} is not finite", u.column + 1, u.key, printable_cell(cell), u.gain);
        }
        if (beyond_log_range(values[k])) {  // the time too: a corrupt stamp of 1e154 s is no time
            return fmt::format("column {} ({}): value {} {}", u.column + 1, u.key, values[k], kBeyondLogRange);
        }
        if (k >= 1 && k <= joints && k <= names.q_bounds.size() && names.q_bounds[k - 1] && !names.q_bounds[k - 1]->holds(values[k])) {
            return fmt::format("column {} ({}): {}", u.column + 1, u.key, names.q_bounds[k - 1]->refusal(values[k]));
        }
    }
    return {};
}

}  // namespace

RawLog parse_raw_log(const std::string& text, const std::string& source, const LogFormat& format, const LogColumnNames& names,
                     const LogReadSettings& settings, LogReadReport& report) {
    const std::size_t joints = format.joints();
    if (names.q.size() != joints || names.tau.size() != joints || (!format.velocities.empty() && names.qd.size() != joints)) {
        throw InputError(fmt::format("{}: the log format {} has {} joints, the column names {}", source, format.source, joints, names.q.size()));
    }
    report.source = source;
    require_readable_log_text(std::string_view(text).substr(0, text.find('\n')), source);
    NumberedLines lines(text);
    const HeaderRow header = read_header(lines, source, format);
    const ColumnPlan plan = plan_columns(format, names, header, source);
    std::size_t width = header.cells.size();
    if (format.header) require_columns_exist(plan, width, header.cells.front(), header.line, "header", "", source, format);

    RawLog raw{CsvTable(source, plan.table_names), {}};  // refuses two columns of one name
    std::vector<std::string_view> cells;
    std::vector<double> values(plan.uses.size());
    double last_time = 0.0;
    std::size_t last_line = 0;
    std::vector<SkippedRow> skipped;
    auto bad_row = [&](const std::string& reason) {
        const std::string message = fmt::format("{}:{}: {}", source, lines.line(), reason);
        if (!settings.skip_bad_rows) throw InputError(message + " (--skip-bad-rows skips such rows and reports them)");
        skipped.push_back({lines.line(), message});
    };
    std::string_view row;
    while (lines.next(row)) {
        if (trim_cell(row).empty()) {
            if (lines.at_end()) break;  // a final empty line
            bad_row("empty line inside the data");
            continue;
        }
        split(row, format.delimiter, cells);
        if (width == 0) {
            // Strictly, the first data row sets the width. With --skip-bad-rows the most common one does: a
            // misaligned first record made every good row "bad" after it.
            // (Counting every row's cells reads the whole text once: only when it is needed.)
            const auto most_common_width = [&] {
                return most_common_cell_count(std::string_view(text).substr(static_cast<std::size_t>(row.data() - text.data())), format.delimiter);
            };
            width = settings.skip_bad_rows ? most_common_width() : cells.size();
            const bool beyond = std::any_of(plan.uses.begin(), plan.uses.end(), [&](const ColumnPlan::Use& u) { return u.column >= width; });
            if (beyond) {
                const std::size_t most = most_common_width();
                const std::string misaligned =
                    most != width ? fmt::format(" (most rows have {}: is this one misaligned? --skip-bad-rows skips it)", most) : std::string();
                require_columns_exist(plan, width, cells.front(), lines.line(), settings.skip_bad_rows ? "most common data row" : "first data row",
                                      misaligned, source, format);
            }
        }
        if (cells.size() != width) {
            bad_row(fmt::format("expected {} columns, found {}", width, cells.size()));
            continue;
        }
        const bool maybe_header = !format.header && raw.lines.empty() && skipped.empty();
        const std::string refusal = read_row_values(cells, plan, names, joints, maybe_header, lines.line(), format, values);
        if (!refusal.empty()) {
            bad_row(refusal);
            continue;
        }
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
            bad_row(fmt::format("column {} (time): time {:.10g} s is not after {:.10g} s of line {} (time must increase)", plan.uses[0].column + 1, values[0],
                                last_time, last_line));
            continue;
        }
        last_time = values[0];
        last_line = lines.line();
        std::size_t k = 0;
        for (std::size_t c = 0; c < plan.table_names.size(); ++c) {
            const bool zero = std::find(plan.zero_torque.begin(), plan.zero_torque.end(), c) != plan.zero_torque.end();
            raw.table.mutable_column(c).push_back(zero ? 0.0 : values[k++]);
        }
        raw.lines.push_back(lines.line());
    }
    if (settings.skip_bad_rows) keep_increasing_times(raw, source, plan.uses[0].column + 1, skipped);
    std::stable_sort(skipped.begin(), skipped.end(), [](const SkippedRow& a, const SkippedRow& b) { return a.line < b.line; });
    for (SkippedRow& r : skipped) {
        report.skipped_lines.push_back(r.line);
        report.skipped.push_back(std::move(r.message));
    }
    report.lines = lines.line();
    report.rows = raw.lines.size();
    return raw;
}

}  // namespace jacobid::io
