// SPDX-License-Identifier: MIT
// Issue 36 ("Bad input, round three"), reading logs: efforts all null, header names that are digits, a null
// time column, implausible sample periods, --max-gap beyond 10 median steps, a corrupt block that
// --skip-bad-rows skips, one-column headers (wrong delimiter), bare-CR line ends, UTF-16 and a byte order
// mark. docs/reliability.md, "Round three (issue 36)", "Reading logs".
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/core.h>

#include <functional>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "input_error_of.hpp"
#include "io/csv_table.hpp"
#include "io/increasing_rows.hpp"
#include "io/log_format.hpp"
#include "io/time_axis.hpp"

namespace {

using namespace jacobid::io;

const auto error_of = jacobid::test::input_error_of;

LogFormat fmt_of(const std::string& yaml) { return parse_log_format(yaml, "f.yaml"); }

// n rows "t,q1,q2,tau1,tau2" from t0 every `step` (in the column's own unit), q1 = 0.01 k, q2 = -0.02 k.
std::string rows(std::size_t n, double step, double t0 = 0.0) {
    std::string s;
    for (std::size_t k = 0; k < n; ++k) {
        const double x = static_cast<double>(k);
        s += fmt::format("{},{},{},{},{}\n", t0 + step * x, 0.01 * x, -0.02 * x, 1.0 + x, 2.0 + x);
    }
    return s;
}

const LogFormat kTwoJoints = parse_log_format("header: false\ntime: {column: 1}\npositions: [2, 3]\ntorques: [4, 5]\n", "two.yaml");

TEST(RoundThreeLogs, EffortsAllNullAreRefusedNamingTheKey) {
    // Every joint null: every torque 0 and every identified parameter exactly 0 with std 0 (exit 0).
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2, 3]\ntorques: [null, null]\n"); }),
              "f.yaml:3:10: torques: every joint is null (no actuator), so no effort is read and there is nothing to identify from: give the "
              "column of at least one joint");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2]\ncurrents: [null]\ngains: [null]\n"); }),
              "f.yaml:3:11: currents: every joint is null (no actuator), so no effort is read and there is nothing to identify from: give the "
              "column of at least one joint");
    // One passive joint (the pendubot's) stays fine.
    EXPECT_NO_THROW(fmt_of("time: {column: 1}\npositions: [2, 3]\ntorques: [4, null]\n"));
}

TEST(RoundThreeLogs, AGainNoMotorHasIsBlamedOnItsKeyNotOnADataCell) {
    // 1e308 N.m/A made the first current cell's torque infinite, and the message blamed that cell.
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2, 3]\ncurrents: [4, 5]\ngains: [2.5, 1e308]\n"); }),
              "f.yaml:4:14: gains[1]: 1e+308 N.m/A is no current-to-torque gain (expected |gain| within 1e-06 .. 1e+06 N.m/A: the motor's "
              "torque constant times the gear ratio)");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2]\ncurrents: [4]\ngains: [-1e-9]\n"); }),
              "f.yaml:4:9: gains[0]: -1e-09 N.m/A is no current-to-torque gain (expected |gain| within 1e-06 .. 1e+06 N.m/A: the motor's "
              "torque constant times the gear ratio)");
    // The shared UR10e format's gains (~10 N.m/A) and the pendubot's negative one stay fine.
    EXPECT_NO_THROW(fmt_of("time: {column: 1}\npositions: [2, 3]\ncurrents: [4, 5]\ngains: [-0.123, 13.5]\n"));
}

TEST(RoundThreeLogs, QuotedDigitsAreHeaderNamesAndPlainNumbersColumnNumbers) {
    // The header names its columns 3 and 2 in the other order: quoted, they are names, so joint 1 reads the
    // column named '3' (the 2nd), not the 3rd column (joints were swapped without a word).
    const LogFormat named = fmt_of("time: {column: t}\npositions: ['3', '2']\ntorques: [a, b]\n");
    EXPECT_EQ(named.positions[0].name, "3");
    EXPECT_EQ(named.positions[0].index, 0u);
    std::string text = "t,3,2,a,b\n";
    for (int k = 0; k < 5; ++k) text += fmt::format("{},{},{},1,2\n", 0.001 * k, 10 + k, 20 + k);
    LogReadReport report;
    const CsvTable t = parse_formatted_log(text, "n.csv", named, LogColumnNames::numbered(2), {}, report);
    EXPECT_EQ(t.column("q1")[2], 12.0);
    EXPECT_EQ(t.column("q2")[2], 22.0);
    // Plain numbers are column numbers, as before.
    const LogFormat numbered = fmt_of("header: false\ntime: {column: 1}\npositions: [3, 2]\ntorques: [4, 5]\n");
    EXPECT_EQ(numbered.positions[0].index, 3u);
    // A quoted number without a header names no column: said so, with how to write a column number.
    EXPECT_EQ(error_of([] { fmt_of("header: false\ntime: {column: 1}\npositions: ['3']\ntorques: [4]\n"); }),
              "f.yaml:3:13: positions[0]: '3' is quoted, so a header name, but header: false (write 3 without quotes for a column number)");
    // A quoted number the header lacks: the message says that quoted is a name.
    const LogFormat missing = fmt_of("time: {column: t}\npositions: ['4']\ntorques: [a]\n");
    EXPECT_EQ(error_of([&] { parse_formatted_log("t,q,a\n0,1,2\n0.001,1,2\n", "m.csv", missing, LogColumnNames::numbered(1), {}, report); }),
              "m.csv:1: positions[0]: no column '4' in the header ('4' is quoted, so a name; write 4 without quotes for a column number) "
              "(columns: t,q,a)");
    // Ambiguous: an unquoted 2 (column 2) while the header names another column '2'.
    const LogFormat ambiguous = fmt_of("time: {column: t}\npositions: [2]\ntorques: [a]\n");
    EXPECT_EQ(error_of([&] { parse_formatted_log("t,a,2\n0,1,2\n0.001,1,2\n", "a.csv", ambiguous, LogColumnNames::numbered(1), {}, report); }),
              "a.csv:1: positions[0]: 2 (unquoted) is column number 2, but the header names column 3 '2': quote it ('2') for the column of that "
              "name, or rename the header");
}

TEST(RoundThreeLogs, ExplicitNullIsNotReportedAsMissing) {
    EXPECT_EQ(error_of([] { fmt_of("time: {column: null}\npositions: [2]\ntorques: [3]\n"); }),
              "f.yaml:1:16: time.column: null, but the time column (a 1-based index or a header name) is required");
    EXPECT_EQ(error_of([] { fmt_of("time: null\npositions: [2]\ntorques: [3]\n"); }),
              "f.yaml:1:7: time: null, but a mapping {column: C, scale: S} is required");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: null\ntorques: [3]\n"); }),
              "f.yaml:2:12: positions: null, but a list of the joints' position columns is required");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2]\ntorques: null\n"); }),
              "f.yaml:3:10: torques: null, but a list of columns, one per joint (null inside it: a joint without actuator) is required");
    // Absent is still "missing".
    EXPECT_EQ(error_of([] { fmt_of("time: {scale: 2}\npositions: [2]\ntorques: [3]\n"); }), "f.yaml:1:7: time.column: missing (required)");
}

TEST(RoundThreeLogs, SamplePeriodsOutsideTenMicrosecondsToOneTenthOfASecondAreRefusedWithTheLikelyUnit) {
    LogReadReport report;
    const auto names = LogColumnNames::numbered(2);
    // A 1 kHz log whose time column is in ms, read as s: steps of 1 s.
    EXPECT_EQ(error_of([&] { parse_formatted_log(rows(20, 1.0), "ms.csv", kTwoJoints, names, {}, report); }),
              "ms.csv: time column 1: the median time step is 1 s, outside the plausible sample periods 10 us .. 100 ms per sample (100 kHz .. 10 Hz): "
              "is the time column in ms (1 ms per sample: time.scale 0.001)? (two.yaml reads it with time.scale 1 s per unit)");
    // Nanosecond stamps read as s: steps of 1e6 s (the old bound, 1000 s, caught these; ms ones passed).
    EXPECT_NE(error_of([&] { parse_formatted_log(rows(20, 1e6), "ns.csv", kTwoJoints, names, {}, report); })
                  .find("the median time step is 1e+06 s, outside the plausible sample periods 10 us .. 100 ms per sample (100 kHz .. 10 Hz): "
                        "is the time column in ns (1 ms per sample: time.scale 1e-09)?"),
              std::string::npos);
    // Seconds read with a nanosecond scale: steps of 1e-12 s.
    const LogFormat ns = parse_log_format("header: false\ntime: {column: 1, scale: 1e-9}\npositions: [2, 3]\ntorques: [4, 5]\n", "ns.yaml");
    EXPECT_EQ(error_of([&] { parse_formatted_log(rows(20, 0.001), "s.csv", ns, names, {}, report); }),
              "s.csv: time column 1: the median time step is 1e-12 s, outside the plausible sample periods 10 us .. 100 ms per sample (100 kHz .. "
              "10 Hz): is the time column in s (1 ms per sample: time.scale 1)? (ns.yaml reads it with time.scale 1e-09 s per unit)");
    // time.scale is the way to read the ms log, and the plain CSV reader says how.
    const LogFormat in_ms = parse_log_format("header: false\ntime: {column: 1, scale: 0.001}\npositions: [2, 3]\ntorques: [4, 5]\n", "ms.yaml");
    EXPECT_NO_THROW(parse_formatted_log(rows(20, 1.0), "ms.csv", in_ms, names, {}, report));
    EXPECT_NEAR(report.grid_period, 0.001, 1e-12);
    const CsvTable plain = parse_csv("t,q1\n" + std::string("0,0\n1,0\n2,0\n"), "p.csv");
    EXPECT_EQ(error_of([&] { check_uniform_time(plain, "t"); }),
              "p.csv: column 't': the median time step is 1 s, outside the plausible sample periods 10 us .. 100 ms per sample (100 kHz .. 10 Hz): "
              "is the time column in ms (1 ms per sample: time.scale 0.001)? (a --log-format file's "
              "time: {column: ..., scale: ...} reads other units)");
    // The bounds themselves are accepted.
    EXPECT_NO_THROW(require_plausible_sample_period(kMinSamplePeriod, "x"));
    EXPECT_NO_THROW(require_plausible_sample_period(kMaxSamplePeriod, "x"));
}

TEST(RoundThreeLogs, MaxGapBeyondTenMedianStepsIsRefused) {
    // A 10 ms log with a 10 s hole: --max-gap 1e6 let the spline bridge it as one step.
    std::string text = rows(30, 0.01) + rows(30, 0.01, 10.3);
    LogReadSettings settings;
    settings.max_gap = 1e6;
    LogReadReport report;
    EXPECT_EQ(error_of([&] { parse_formatted_log(text, "h.csv", kTwoJoints, LogColumnNames::numbered(2), settings, report); }),
              "h.csv: --max-gap 1e+06 s is 1e+08 median steps of 10 ms, more than the 10 median steps (100 ms) a single step may span: a longer "
              "step is always a gap (--on-gap interpolate bridges one of up to --interpolate-max samples and names it, --on-gap split cuts the log "
              "there)");
    settings.max_gap = 0.1;  // 10 median steps: the most allowed; the hole is still a gap
    EXPECT_NE(error_of([&] { parse_formatted_log(text, "h.csv", kTwoJoints, LogColumnNames::numbered(2), settings, report); }).find("h.csv:31: time step"),
              std::string::npos);
}

TEST(RoundThreeLogs, LongestIncreasingTimesKeepTheMostRowsAndTheEarliest) {
    EXPECT_EQ(longest_increasing_times({}), std::vector<bool>{});
    EXPECT_EQ(longest_increasing_times({1e154, 1, 2, 3}), (std::vector<bool>{false, true, true, true}));
    EXPECT_EQ(longest_increasing_times({1, 2, 2, 3}), (std::vector<bool>{true, true, false, true}));  // the first of equal times
    EXPECT_EQ(longest_increasing_times({5, 6, 1, 2, 3}), (std::vector<bool>{false, false, true, true, true}));
    EXPECT_EQ(longest_increasing_times({1, 2, 9, 3, 4}), (std::vector<bool>{true, true, false, true, true}));
    EXPECT_EQ(longest_increasing_times({3, 2, 1}), (std::vector<bool>{true, false, false}));
    // Many random cases: the kept times increase and no single skipped row could be added back.
    unsigned seed = 12345;
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<double> t(40);
        for (double& v : t) v = static_cast<double>((seed = seed * 1103515245u + 12345u) >> 16 & 63u);
        const std::vector<bool> keep = longest_increasing_times(t);
        double previous = -1.0;
        std::size_t kept = 0;
        for (std::size_t i = 0; i < t.size(); ++i) {
            if (!keep[i]) continue;
            EXPECT_GT(t[i], previous);
            previous = t[i];
            ++kept;
        }
        // Against a quadratic longest-run count.
        std::vector<std::size_t> ending(t.size(), 1);
        std::size_t best = t.empty() ? 0 : 1;
        for (std::size_t i = 0; i < t.size(); ++i) {
            for (std::size_t j = 0; j < i; ++j) {
                if (t[j] < t[i]) ending[i] = std::max(ending[i], ending[j] + 1);
            }
            best = std::max(best, ending[i]);
        }
        EXPECT_EQ(kept, best) << trial;
    }
}

// The block a real UR10e recording starts with (issue 36): a misaligned record, times of 1e154, a position of
// 253 rad, rows of zeros, then the clean rows. --skip-bad-rows skipped the misaligned row and then every clean
// row as "not after 1e154 s", so the corrupt rows were the log: "the median time step is 2.68e+154 s".
TEST(RoundThreeLogs, SkipBadRowsSkipsACorruptBlockAndListsItsLines) {
    std::string text = "1,2,3\n";                      // line 1: misaligned
    text += "1e154,0,0,1,2\n2.68e154,0,0,1,2\n";      // lines 2-3: times of 1e154 (beyond +-1e30)
    text += "5e29,253,0,1,2\n6e29,253,0,1,2\n";       // lines 4-5: within the bound, out of order with the clean rows
    text += "0,0,0,0,0\n0,0,0,0,0\n0,0,0,0,0\n";      // lines 6-8: zero-filled records
    text += "3,0,0,0,0\n";                            // line 9: zeros with a time
    text += rows(50, 0.01, 388.0);                     // lines 10-59
    LogReadSettings settings;
    settings.skip_bad_rows = true;
    LogReadReport report;
    const CsvTable t = parse_formatted_log(text, "c.csv", kTwoJoints, LogColumnNames::numbered(2), settings, report);
    EXPECT_EQ(report.rows, 50u);
    EXPECT_NEAR(report.median_step, 0.01, 1e-9);
    EXPECT_NEAR(t.column("t").front(), 388.0, 1e-9);
    EXPECT_EQ(report.skipped_lines, (std::vector<std::size_t>{1, 2, 3, 4, 5, 6, 7, 8, 9}));
    ASSERT_EQ(report.skipped.size(), 9u);
    EXPECT_EQ(report.skipped[0], "c.csv:1: expected 5 columns, found 3");
    EXPECT_EQ(report.skipped[1],
              "c.csv:2: column 1 (time): value 1e+154 is beyond +-1e30, which no measurement is (an outlier? its square would overflow the identification)");
    EXPECT_EQ(report.skipped[3],
              "c.csv:4: column 1 (time): time 5e+29 s is not before 388 s of line 10, where the increasing times go on (time must increase)");
    EXPECT_EQ(report.skipped[5], "c.csv:6: every value but the time is 0 (a zero-filled record, not a sample)");
    EXPECT_EQ(report.skipped[8], "c.csv:9: every value but the time is 0 (a zero-filled record, not a sample)");
    EXPECT_NE(report.summary().find("50 rows read, 9 bad rows skipped (lines 1-9; first: c.csv:1: expected 5 columns, found 3)"), std::string::npos)
        << report.summary();
    // Without --skip-bad-rows the first line is named: the first data row sets the width.
    EXPECT_EQ(error_of([&] { parse_formatted_log(text, "c.csv", kTwoJoints, LogColumnNames::numbered(2), {}, report); }),
              "c.csv:1: torques[0]: column 4 does not exist, the first data row has 3 columns (most rows have 5: is this one misaligned? "
              "--skip-bad-rows skips it)");
}

TEST(RoundThreeLogs, ZeroRowsAreOnlySkippedWithSkipBadRows) {
    // A synthetic log that starts at t = 0 with every value 0 loads as it is.
    const std::string text = "0,0,0,0,0\n" + rows(10, 0.01, 0.01);
    LogReadReport report;
    EXPECT_NO_THROW(parse_formatted_log(text, "z.csv", kTwoJoints, LogColumnNames::numbered(2), {}, report));
    EXPECT_EQ(report.rows, 11u);
    // With --skip-bad-rows it counts as a zero-filled record, skipped and named.
    LogReadSettings settings;
    settings.skip_bad_rows = true;
    LogReadReport lenient;
    parse_formatted_log(text, "z.csv", kTwoJoints, LogColumnNames::numbered(2), settings, lenient);
    EXPECT_EQ(lenient.rows, 10u);
    EXPECT_EQ(lenient.skipped, (std::vector<std::string>{"z.csv:1: every value but the time is 0 (a zero-filled record, not a sample)"}));
}

TEST(RoundThreeLogs, OneColumnHeaderNamesTheDelimiter) {
    // A ';' file read with ',': one column, which was listed as if it were the columns.
    EXPECT_EQ(error_of([] { parse_csv("t;q1;tau1\n0;1;2\n", "semi.csv"); }),
              "semi.csv:1: the header 't;q1;tau1' is one column: is the delimiter ';'? (this reader takes ','; a --log-format with delimiter: ';' "
              "reads it)");
    EXPECT_EQ(error_of([] { parse_csv("t\tq1\ttau1\n0\t1\t2\n", "tab.csv"); }),
              "tab.csv:1: the header 't\\tq1\\ttau1' is one column: is the delimiter '\\t'? (this reader takes ','; a --log-format with delimiter: "
              "'\\t' reads it)");
    const LogFormat named = fmt_of("time: {column: t}\npositions: [q1]\ntorques: [tau1]\n");
    LogReadReport report;
    EXPECT_EQ(error_of([&] { parse_formatted_log("t;q1;tau1\n0;1;2\n", "semi.csv", named, LogColumnNames::numbered(1), {}, report); }),
              "semi.csv:1: time.column: no column 't': the header is one column 't;q1;tau1': is the delimiter ';'? (f.yaml says delimiter: ',')");
    const LogFormat numbered = fmt_of("header: false\ntime: {column: 1}\npositions: [2]\ntorques: [3]\n");
    EXPECT_EQ(error_of([&] { parse_formatted_log("0;1;2\n", "semi.csv", numbered, LogColumnNames::numbered(1), {}, report); }),
              "semi.csv:1: positions[0]: column 2 does not exist, the first data row has 1 columns: is the delimiter ';'? (f.yaml says delimiter: ',')");
}

TEST(RoundThreeLogs, BareCarriageReturnsUtf16AndByteOrderMarks) {
    // Old-Mac line ends: the whole file was one line, read as a header and 0 rows.
    EXPECT_EQ(error_of([] { parse_csv("t,q1\r0,1\r0.001,2\r", "cr.csv"); }),
              "cr.csv:1: the line ends are bare carriage returns (CR, old Mac style), so the whole file reads as one line: save it with LF or CRLF line "
              "ends");
    EXPECT_EQ(parse_csv("t,q1\r\n0,1\r\n0.001,2\r\n", "crlf.csv").rows(), 2u);  // CRLF stays accepted
    LogReadReport report;
    EXPECT_EQ(error_of([&] { parse_formatted_log("0,0,0,1,2\r0.001,0,0,1,2\r", "cr.csv", kTwoJoints, LogColumnNames::numbered(2), {}, report); }),
              "cr.csv:1: the line ends are bare carriage returns (CR, old Mac style), so the whole file reads as one line: save it with LF or CRLF line "
              "ends");
    // UTF-16 (a spreadsheet's "Unicode text"): NUL between the characters.
    const std::string utf16("\xFF\xFEt\0,\0q\0\n\0", 10);
    EXPECT_EQ(error_of([&] { parse_csv(utf16, "u16.csv"); }),
              "u16.csv:1: the file is encoded as UTF-16 (NUL bytes between the characters): save it as UTF-8 or ASCII text");
    // Bytes FE and FF, which UTF-8 never holds, anywhere in the first line (fuzz_csv_log: a name starting with
    // FE FF after tabs was accepted, and the table printed again began with a UTF-16 byte order mark).
    EXPECT_EQ(error_of([] { parse_csv("\t\t\xFE\xFF\xFF\xEBt,q\n0,1\n", "fe.csv"); }),
              "fe.csv:1: byte 3 is 0xFE, which UTF-8 text never holds: another encoding (Latin-1?) or a binary file; save it as UTF-8 or ASCII text");
    EXPECT_EQ(error_of([] { parse_csv("t,q\xFF\n0,1\n", "latin1.csv"); }),
              "latin1.csv:1: byte 4 is 0xFF, which UTF-8 text never holds: another encoding (Latin-1?) or a binary file; save it as UTF-8 or ASCII text");
    EXPECT_EQ(parse_csv("t,q\xC3\xBF\n0,1\n", "utf8.csv").header()[1], "q\xC3\xBF");  // the same letter in UTF-8 stays a name
    // Magic numbers where the first name starts, after blanks (fuzz_csv_log: '\t\xFD7zXZ1,...' was accepted, its
    // printed copy refused as xz); a first name that merely starts with "BZh" is a name.
    EXPECT_EQ(error_of([] { parse_csv(std::string(" \t\x1F\x8B\x08\x00junk", 10), "gz.csv"); }),
              "gz.csv:1: the file is compressed (gzip, zip, xz or bzip2): unpack it and give the CSV");
    EXPECT_EQ(error_of([] { parse_csv("BZh91AY&SY\n", "bz.csv"); }), "bz.csv:1: the file is compressed (gzip, zip, xz or bzip2): unpack it and give the CSV");
    EXPECT_EQ(parse_csv("BZhang,q\n0,1\n", "names.csv").header()[0], "BZhang");
    // Compressed and binary files are named as such, not as odd columns or UTF-16.
    EXPECT_EQ(error_of([] { parse_csv(std::string("\x1F\x8B\x08\x00junk", 8), "p.csv.gz"); }),
              "p.csv.gz:1: the file is compressed (gzip, zip, xz or bzip2): unpack it and give the CSV");
    EXPECT_EQ(error_of([] { parse_csv(std::string("t,q\0\x01\x02\x03" "abcdefgh\n", 16), "bin.csv"); }),
              "bin.csv:1: the file holds control characters (NUL, ...): a binary file, not a text log");
    EXPECT_EQ(error_of([] { parse_csv(std::string("t,q\x01\x7f\rab\n", 9), "bin.csv"); }),
              "bin.csv:1: the file holds control characters (NUL, ...): a binary file, not a text log");  // not "bare CR"
    // A header where there is none, and none where there is one.
    const LogFormat named = fmt_of("time: {column: t}\npositions: [q1, q2]\ntorques: [tau1, tau2]\n");
    EXPECT_EQ(error_of([&] { parse_formatted_log(rows(3, 0.001), "nh.csv", named, LogColumnNames::numbered(2), {}, report); }),
              "nh.csv:1: time.column: no column 't' in the header (columns: 0,0,-0,1,2); that line is all numbers: has the log no header? (header: "
              "false in f.yaml)");
    EXPECT_EQ(error_of([&] { parse_formatted_log("t,q1,q2,tau1,tau2\n" + rows(3, 0.001), "h.csv", kTwoJoints, LogColumnNames::numbered(2), {}, report); }),
              "h.csv:1: column 1 (time): expected a number, got 't' (is line 1 a header? header: true or skip_rows in two.yaml) (--skip-bad-rows "
              "skips such rows and reports them)");
    EXPECT_EQ(error_of([] { parse_csv(std::string(64, '\0'), "zeros.bin"); }),
              "zeros.bin:1: the file holds control characters (NUL, ...): a binary file, not a text log");  // NUL everywhere: not UTF-16
    EXPECT_EQ(error_of([] { parse_csv(std::string("t\0,\0q\0\n\0", 9), "u16le.csv"); }),
              "u16le.csv:1: the file is encoded as UTF-16 (NUL bytes between the characters): save it as UTF-8 or ASCII text");
    // A decimal comma (a ';' export of a comma locale) is named as one.
    const LogFormat semicolons = parse_log_format("header: false\ndelimiter: ';'\ntime: {column: 1}\npositions: [2]\ntorques: [3]\n", "sc.yaml");
    EXPECT_EQ(error_of([&] { parse_formatted_log("0;0,5;1\n", "dc.csv", semicolons, LogColumnNames::numbered(1), {}, report); }),
              "dc.csv:1: column 2 (positions[0]): expected a number, got '0,5' (a decimal comma? numbers are read with a '.') (--skip-bad-rows skips "
              "such rows and reports them)");
    // A UTF-8 byte order mark before the first data row of a raw log is not part of its time cell.
    const CsvTable t = parse_formatted_log("\xEF\xBB\xBF" + rows(5, 0.01), "bom.csv", kTwoJoints, LogColumnNames::numbered(2), {}, report);
    EXPECT_EQ(t.rows(), 5u);
}

}  // namespace
