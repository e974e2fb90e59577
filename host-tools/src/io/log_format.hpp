// SPDX-License-Identifier: MIT
#pragma once
// Raw robot logs as real controllers write them (docs/log-format.md): a YAML "log format" says which
// column is time, which are the joints' positions, measured velocities, torques or motor currents (with
// their current-to-torque gains), whether there is a header, the delimiter and the lines to skip. The reader
// turns such a log into the normalized table the rest of the host tools consume (io::CsvTable with columns
// named as the robot description expects: t, q1.., qd1.., tau1..), on a uniform time grid
// (io/resample.hpp; the choice and its measured accuracy: docs/method.md, "Non-uniform sampling").
// Every problem is an InputError naming file:line (and column or key); with skip_bad_rows, malformed rows
// and rows whose time does not increase are skipped and each one is reported instead.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "io/csv_table.hpp"
#include "io/position_bounds.hpp"

namespace jacobid::io {

// A column of the raw log: a 1-based index or a header name; neither (YAML null) = not logged.
struct ColumnRef {
    std::size_t index = 0;  // 1-based, 0 when given by name or absent
    std::string name;
    bool present() const { return index > 0 || !name.empty(); }
};

struct LogFormat {
    std::string source;  // the YAML file, for messages
    bool header = true;
    char delimiter = ',';
    std::size_t skip_rows = 0;  // lines skipped before the header (or the first data row)
    ColumnRef time;
    double time_scale = 1.0;  // seconds per unit of the time column
    std::vector<ColumnRef> positions;
    std::vector<ColumnRef> velocities;  // empty: none logged; an absent entry: not logged for that joint
    // The reference the controller tracked (references: [q_ref.., qd_ref..], 2 x joints columns), loaded as
    // q_refJ, qd_refJ (what identify --estimator iv | didim simulate along); empty: not logged.
    std::vector<ColumnRef> references;
    std::vector<ColumnRef> efforts;     // torques, or currents; an absent entry: no actuator (torque 0)
    bool currents = false;
    std::vector<double> gains;  // tau = gain * effort, per joint (1 for torques)
    std::size_t joints() const { return positions.size(); }
};

// Unknown keys, wrong types and inconsistent lists are InputError("file:line:col: key: ...").
LogFormat parse_log_format(const std::string& yaml_text, const std::string& source);
LogFormat load_log_format(const std::string& path);

// Split: each run of rows between gaps is a segment of its own (parse_formatted_log_segments), all on one grid period.
enum class GapPolicy { Error, Interpolate, Split };

// The longest step --max-gap may let pass as a step, in median steps: beyond, the spline would bridge a hole
// without a word (--max-gap 1e6 regridded a 10 s hole of a 10 ms log). Longer holes are gaps, which
// --on-gap interpolate bridges only up to --interpolate-max samples, naming each.
constexpr double kMaxGapMedianSteps = 10.0;

struct LogReadSettings {
    bool skip_bad_rows = false;
    GapPolicy on_gap = GapPolicy::Error;
    double max_gap = 0.0;              // s; a longer step is a gap. 0: 3 median steps; at most kMaxGapMedianSteps
    std::size_t interpolate_max = 10;  // grid samples a gap may span with --on-gap interpolate
    double period = 0.0;               // s, of the uniform grid; 0: the mean step (gaps excluded)
};

// A contiguous run of rows without a gap, resampled on its own uniform grid (which starts at its first row).
struct LogSegment {
    std::size_t first_line = 0, last_line = 0;  // lines of its first and last rows
    std::size_t rows = 0;                       // raw rows
    double start = 0.0, duration = 0.0;         // s: its first row's time, last minus first
    std::size_t samples = 0;                    // on its uniform grid
    std::string describe() const;               // "lines 12-501: 4.95 s, 990 samples"
};

// What the reader found and did, printed on stderr by the commands and checked by the tests.
struct LogReadReport {
    std::string source;
    std::size_t lines = 0;             // lines in the file
    std::size_t rows = 0;              // data rows kept
    std::vector<std::string> skipped;  // "file:line: reason", one per skipped row, in line order
    std::vector<std::size_t> skipped_lines;  // their lines
    double median_step = 0.0;          // s
    // Steps farther than half a median step from the median (e.g. the UR10e's 2 ms steps), each reported.
    std::vector<std::size_t> irregular_lines;  // line of the row that ends the step
    std::vector<double> irregular_steps;       // s
    std::vector<std::size_t> gap_lines;        // gaps (> max_gap), interpolated or split at
    std::vector<double> gap_steps;
    bool split = false;                        // --on-gap split: the gaps cut the log into `segments`
    std::vector<LogSegment> segments;          // one per table returned (one without split)
    double grid_period = 0.0;  // s, of the uniform grid
    double grid_start = 0.0;   // s
    std::size_t samples = 0;   // on the uniform grid
    // One paragraph: rows, skipped rows (their lines as ranges) (first at line L: 2.0 ms), gaps, segments, the grid.
    std::string summary() const;
};

// Names of the normalized table's columns (a robot description's, or q1.., qd1.., tau1..).
struct LogColumnNames {
    std::string time = "t";
    std::vector<std::string> q, qd, tau;
    // Per joint (empty, or one per joint): where its positions may be; a raw row beyond is a bad row.
    std::vector<std::optional<PositionBounds>> q_bounds;
    static LogColumnNames numbered(std::size_t joints, const std::string& time = "t");
};

// The raw rows at their own times: columns time (s), q.., qd.. (logged ones only), tau.. (gain applied,
// 0 for a joint without actuator). Line numbers of kept rows in `lines`.
struct RawLog {
    CsvTable table;
    std::vector<std::size_t> lines;
};
RawLog parse_raw_log(const std::string& text, const std::string& source, const LogFormat& format, const LogColumnNames& names,
                     const LogReadSettings& settings, LogReadReport& report);

// Reads `path` with `format` and resamples it onto a uniform grid (io/resample.hpp); fills `report`.
CsvTable read_formatted_log(const std::string& path, const LogFormat& format, const LogColumnNames& names,
                            const LogReadSettings& settings, LogReadReport& report);
// Same from text in memory. With GapPolicy::Split a log that has gaps is an InputError at its first gap
// (one table cannot hold segments): read it with the _segments functions below.
CsvTable parse_formatted_log(const std::string& text, const std::string& source, const LogFormat& format, const LogColumnNames& names,
                             const LogReadSettings& settings, LogReadReport& report);

// Every policy: the log as segments, one table per report.segments entry, each on its own uniform grid with
// one period for all (the imposed one, or the mean non-gap step over the whole log), times kept. Without
// GapPolicy::Split this is the single table of parse_formatted_log. A segment of a single row is a table of
// one sample. Tables are named "source (lines a-b)" when there are several, for the messages of their users.
std::vector<CsvTable> parse_formatted_log_segments(const std::string& text, const std::string& source, const LogFormat& format,
                                                   const LogColumnNames& names, const LogReadSettings& settings, LogReadReport& report);
std::vector<CsvTable> read_formatted_log_segments(const std::string& path, const LogFormat& format, const LogColumnNames& names,
                                                  const LogReadSettings& settings, LogReadReport& report);

}  // namespace jacobid::io
