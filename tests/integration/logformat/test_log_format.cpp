// SPDX-License-Identifier: MIT
// The YAML log format (every key, unknown keys, header names, null, gain signs, delimiter, skip_rows) and
// the raw-log reader's errors and reports (bad rows, non-increasing time, --skip-bad-rows, gaps, irregular
// steps), byte-exact on the messages users see.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "core/errors.hpp"
#include "input_error_of.hpp"
#include "identify/plan/log_columns.hpp"
#include "io/log_format.hpp"
#include "robot/robot_description.hpp"

namespace {

using jacobid::InputError;
using namespace jacobid::io;

const auto error_of = jacobid::test::input_error_of;

LogFormat fmt_of(const std::string& yaml) { return parse_log_format(yaml, "f.yaml"); }

TEST(LogFormat, Ur10eExampleFromTheIssue) {
    const LogFormat f = fmt_of(
        "{header: false, time: {column: 1}, positions: [2,3,4,5,6,7], currents: [14,15,16,17,18,19],\n"
        " gains: [10.0, 10.6956, 8.4566, 9.0029, 9.48, 10.1232]}");
    EXPECT_FALSE(f.header);
    EXPECT_EQ(f.delimiter, ',');
    EXPECT_EQ(f.skip_rows, 0u);
    EXPECT_EQ(f.time.index, 1u);
    EXPECT_EQ(f.time_scale, 1.0);
    ASSERT_EQ(f.joints(), 6u);
    EXPECT_EQ(f.positions[5].index, 7u);
    EXPECT_TRUE(f.velocities.empty());
    EXPECT_TRUE(f.currents);
    EXPECT_EQ(f.efforts[0].index, 14u);
    EXPECT_EQ(f.gains[1], 10.6956);
}

TEST(LogFormat, EveryKeyWithHeaderNamesAndNull) {
    const LogFormat f = fmt_of(
        "header: true\ndelimiter: ';'\nskip_rows: 2\ntime: {column: stamp, scale: 0.001}\npositions: [p1, 3]\n"
        "velocities: [v1, null]\ntorques: [t1, null]\n");
    EXPECT_TRUE(f.header);
    EXPECT_EQ(f.delimiter, ';');
    EXPECT_EQ(f.skip_rows, 2u);
    EXPECT_EQ(f.time.name, "stamp");
    EXPECT_EQ(f.time_scale, 0.001);
    EXPECT_EQ(f.positions[0].name, "p1");
    EXPECT_EQ(f.positions[1].index, 3u);
    EXPECT_TRUE(f.velocities[0].present());
    EXPECT_FALSE(f.velocities[1].present());
    EXPECT_FALSE(f.currents);
    EXPECT_FALSE(f.efforts[1].present());
    EXPECT_EQ(f.gains, (std::vector<double>{1.0, 1.0}));
}

TEST(LogFormat, ErrorsNameTheKeyAndPosition) {
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2]\ntorques: [3]\ncolour: red\n"); }),
              "f.yaml:4:1: colour: unknown key (known: currents, delimiter, gains, header, positions, references, skip_rows, time, torques, velocities)");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1, offset: 2}\npositions: [2]\ntorques: [3]\n"); }),
              "f.yaml:1:19: time.offset: unknown key (known: column, scale)");
    EXPECT_EQ(error_of([] { fmt_of("header: false\ntime: {column: t}\npositions: [2]\ntorques: [3]\n"); }),
              "f.yaml:2:16: time.column: 't' is a header name, but header: false (give a 1-based column index)");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 0}\npositions: [2]\ntorques: [3]\n"); }),
              "f.yaml:1:16: time.column: column index '0' must be an integer >= 1 (columns are counted from 1)");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2, null]\ntorques: [3, 4]\n"); }),
              "f.yaml:2:16: positions[1]: null is not allowed here (only for velocities, torques and currents)");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2, 3]\ntorques: [4]\n"); }),
              "f.yaml:3:10: torques: must be a list of 2 columns (one per joint, as positions)");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2]\ntorques: [3]\ncurrents: [4]\ngains: [1]\n"); }),
              "f.yaml:4:11: currents: give either torques or currents (with gains), not both");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2]\ncurrents: [4]\n"); }),
              "f.yaml:1:1: gains: missing: currents need gains (N.m/A, tau = gain * current; null for a joint without actuator)");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2]\ntorques: [4]\ngains: [2]\n"); }),
              "f.yaml:4:8: gains: gains scale currents: use them with currents, not torques");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2, 3]\ncurrents: [4, null]\ngains: [1, 2]\n"); }),
              "f.yaml:4:12: gains[1]: currents[1] is null (no actuator): its gain must be null too");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\npositions: [2]\ncurrents: [4]\ngains: [0]\n"); }),
              "f.yaml:4:9: gains[0]: a gain of 0 discards the current: use null in currents for a joint without actuator");
    EXPECT_EQ(error_of([] { fmt_of("delimiter: '.'\ntime: {column: 1}\npositions: [2]\ntorques: [3]\n"); }),
              "f.yaml:1:12: delimiter: '.' must be one character that cannot appear in a number, e.g. ',' ';' or \"\\t\"");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1}\ntorques: [3]\n"); }), "f.yaml:1:1: positions: missing (required): the joints' position columns");
    EXPECT_EQ(error_of([] { fmt_of("time: {scale: 2}\npositions: [2]\ntorques: [3]\n"); }), "f.yaml:1:7: time.column: missing (required)");
    EXPECT_EQ(error_of([] { fmt_of("time: {column: 1, scale: -1}\npositions: [2]\ntorques: [3]\n"); }),
              "f.yaml:1:26: time.scale: must be > 0 (seconds per unit of the time column)");
    EXPECT_EQ(error_of([] { fmt_of("skip_rows: -1\ntime: {column: 1}\npositions: [2]\ntorques: [3]\n"); }),
              "f.yaml:1:12: skip_rows: must be an integer in 0..1000000");
}

const LogFormat kPendubotLike = parse_log_format("header: false\ntime: {column: 1}\npositions: [2, 3]\ncurrents: [6, null]\ngains: [-0.123, null]\n", "p.yaml");

std::string uniform_rows(std::size_t n, double step) {
    std::string s;
    for (std::size_t i = 0; i < n; ++i) s += std::to_string(100.0 + step * static_cast<double>(i)) + "," + std::to_string(0.01 * static_cast<double>(i)) + ",0.5,7,8,2\n";
    return s;
}

TEST(LogFormat, GainSignAndNullJointGiveTorques) {
    LogReadReport report;
    const CsvTable t = parse_formatted_log(uniform_rows(20, 0.005), "log.csv", kPendubotLike, LogColumnNames::numbered(2), {}, report);
    ASSERT_EQ(t.header(), (std::vector<std::string>{"t", "q1", "q2", "tau1", "tau2"}));
    EXPECT_EQ(t.rows(), 20u);
    EXPECT_NEAR(t.column("tau1")[5], -0.246, 1e-12);  // -0.123 * 2 A: the negative gain flips the sign
    EXPECT_EQ(t.column("tau2")[5], 0.0);               // no actuator
    EXPECT_NEAR(t.column("q1")[7], 0.07, 1e-12);
    EXPECT_NEAR(t.column("t")[19] - t.column("t")[0], 19 * 0.005, 1e-9);
    EXPECT_EQ(report.summary(), "log.csv: 20 rows read; median step 5 ms; no irregular steps; resampled (cubic spline) onto 20 samples every 5 ms");
}

TEST(LogFormat, HeaderNamesDelimiterSkipRowsAndVelocities) {
    const LogFormat f = parse_log_format(
        "delimiter: ';'\nskip_rows: 2\ntime: {column: ms, scale: 0.001}\npositions: [a]\nvelocities: [va]\ncurrents: [i]\ngains: [2.5]\n", "h.yaml");
    std::string text = "# recorder v1\n# units: ms, rad, A\nms; i; a; va\n";
    for (int k = 0; k < 10; ++k) text += std::to_string(10 * k) + "; " + std::to_string(0.1 * k) + "; " + std::to_string(k) + "; 3\n";
    LogReadReport report;
    const CsvTable t = parse_formatted_log(text, "h.csv", f, LogColumnNames::numbered(1), {}, report);
    ASSERT_EQ(t.header(), (std::vector<std::string>{"t", "q1", "qd1", "tau1"}));
    EXPECT_NEAR(t.column("t")[3], 0.03, 1e-12);
    EXPECT_NEAR(t.column("q1")[4], 4.0, 1e-12);
    EXPECT_NEAR(t.column("qd1")[4], 3.0, 1e-12);
    EXPECT_NEAR(t.column("tau1")[4], 1.0, 1e-12);
    const LogFormat missing = parse_log_format("time: {column: ms}\npositions: [b]\ntorques: [i]\n", "m.yaml");
    EXPECT_EQ(error_of([&] { parse_formatted_log("ms,i,a\n1,2,3\n", "m.csv", missing, LogColumnNames::numbered(1), {}, report); }),
              "m.csv:1: positions[0]: no column 'b' in the header (columns: ms,i,a)");
    const LogFormat wide = parse_log_format("header: false\ntime: {column: 1}\npositions: [2]\ntorques: [9]\n", "w.yaml");
    EXPECT_EQ(error_of([&] { parse_formatted_log("1,2,3\n2,2,3\n", "w.csv", wide, LogColumnNames::numbered(1), {}, report); }),
              "w.csv:1: torques[0]: column 9 does not exist, the first data row has 3 columns");
}

TEST(LogFormat, BadRowsAreErrorsNamingLineAndColumn) {
    LogReadReport report;
    const auto names = LogColumnNames::numbered(2);
    std::string text = uniform_rows(5, 0.005);
    text += "100.025,0.05,abc,7,8,2\n" + uniform_rows(0, 0.005);
    EXPECT_EQ(error_of([&] { parse_formatted_log(text, "b.csv", kPendubotLike, names, {}, report); }),
              "b.csv:6: column 3 (positions[1]): expected a number, got 'abc' (--skip-bad-rows skips such rows and reports them)");
    EXPECT_EQ(error_of([&] { parse_formatted_log(uniform_rows(3, 0.005) + "100.015,1,2\n", "c.csv", kPendubotLike, names, {}, report); }),
              "c.csv:4: expected 6 columns, found 3 (--skip-bad-rows skips such rows and reports them)");
    EXPECT_EQ(error_of([&] { parse_formatted_log(uniform_rows(3, 0.005) + "100.010,1,2,3,4,5\n", "d.csv", kPendubotLike, names, {}, report); }),
              "d.csv:4: column 1 (time): time 100.01 s is not after 100.01 s of line 3 (time must increase) (--skip-bad-rows skips such rows and "
              "reports them)");
    EXPECT_EQ(error_of([&] { parse_formatted_log(uniform_rows(3, 0.005) + "100.015,1,nan,3,4,5\n", "e.csv", kPendubotLike, names, {}, report); }),
              "e.csv:4: column 3 (positions[1]): value 'nan' is not finite (NaN or Inf) (--skip-bad-rows skips such rows and reports them)");
}

TEST(LogFormat, SkipBadRowsReportsEachOne) {
    LogReadSettings settings;
    settings.skip_bad_rows = true;
    std::string text = uniform_rows(4, 0.005);
    text += "100.020,0.04,x,7,8,2\n100.010,0.04,0.5,7,8,2\n\n100.020,0.04,0.5,7,8\n" + std::string("100.020,0.04,0.5,7,8,2\n100.025,0.05,0.5,7,8,2\n");
    LogReadReport report;
    const CsvTable t = parse_formatted_log(text, "s.csv", kPendubotLike, LogColumnNames::numbered(2), settings, report);
    ASSERT_EQ(report.skipped.size(), 4u);
    EXPECT_EQ(report.skipped[0], "s.csv:5: column 3 (positions[1]): expected a number, got 'x'");
    EXPECT_EQ(report.skipped[1], "s.csv:6: column 1 (time): time 100.01 s is not after 100.015 s of line 4 (time must increase)");
    EXPECT_EQ(report.skipped[2], "s.csv:7: empty line inside the data");
    EXPECT_EQ(report.skipped[3], "s.csv:8: expected 6 columns, found 5");
    EXPECT_EQ(report.rows, 6u);
    EXPECT_EQ(t.rows(), 6u);
    EXPECT_EQ(report.summary(),
              "s.csv: 6 rows read, 4 bad rows skipped (lines 5-8; first: s.csv:5: column 3 (positions[1]): expected a number, got 'x'); median step 5 ms; "
              "no irregular steps; resampled (cubic spline) onto 6 samples every 5 ms");
}

std::string clock_rows(const std::vector<double>& steps) {
    std::string s;
    double t = 10.0;
    for (std::size_t i = 0; i <= steps.size(); ++i) {
        s += std::to_string(t) + "," + std::to_string(std::sin(t)) + ",0,0,0,1\n";
        if (i < steps.size()) t += steps[i];
    }
    return s;
}

TEST(LogFormat, IrregularStepsAreNamedByLine) {
    std::vector<double> steps;
    for (int i = 0; i < 40; ++i) steps.push_back(i % 3 == 2 ? 0.012 : 0.010);
    steps[20] = 0.002;
    LogReadReport report;
    const CsvTable t = parse_formatted_log(clock_rows(steps), "u.csv", kPendubotLike, LogColumnNames::numbered(2), {}, report);
    ASSERT_EQ(report.irregular_lines, (std::vector<std::size_t>{22}));
    EXPECT_NEAR(report.irregular_steps[0], 0.002, 1e-9);
    EXPECT_NE(report.summary().find("1 irregular step (first at line 22: 2 ms)"), std::string::npos) << report.summary();
    // The grid period is the mean step; the grid stays inside the log.
    EXPECT_NEAR(report.grid_period, (0.4 + 13 * 0.002 - 0.010) / 40.0, 1e-9);
    EXPECT_LE(t.column("t").back(), 10.0 + 0.4 + 13 * 0.002 - 0.010 + 1e-9);
}

TEST(LogFormat, GapPolicies) {
    std::vector<double> steps(30, 0.005);
    steps[10] = 0.030;  // 5 missing samples
    const auto names = LogColumnNames::numbered(2);
    LogReadReport report;
    EXPECT_EQ(error_of([&] { parse_formatted_log(clock_rows(steps), "g.csv", kPendubotLike, names, {}, report); }),
              "g.csv:12: time step 30 ms after line 11 is a gap (longer than --max-gap 15 ms); --on-gap interpolate fills gaps of up to "
              "--interpolate-max samples, --on-gap split cuts the log there");
    LogReadSettings settings;
    settings.on_gap = GapPolicy::Interpolate;
    settings.interpolate_max = 4;
    EXPECT_EQ(error_of([&] { parse_formatted_log(clock_rows(steps), "g.csv", kPendubotLike, names, settings, report); }),
              "g.csv:12: time step 30 ms after line 11 is a gap of 5 samples, more than --interpolate-max 4");
    settings.interpolate_max = 5;
    LogReadReport ok;
    const CsvTable t = parse_formatted_log(clock_rows(steps), "g.csv", kPendubotLike, names, settings, ok);
    EXPECT_EQ(ok.gap_lines, (std::vector<std::size_t>{12}));
    EXPECT_NEAR(ok.grid_period, 0.005, 1e-12);  // gaps do not stretch the grid period
    EXPECT_EQ(t.rows(), 36u);
    EXPECT_NE(ok.summary().find("1 gap interpolated (first at line 12: 30 ms)"), std::string::npos) << ok.summary();
    // A larger --max-gap makes the same step an irregular one instead.
    LogReadSettings wide;
    wide.max_gap = 0.05;
    LogReadReport r2;
    parse_formatted_log(clock_rows(steps), "g.csv", kPendubotLike, names, wide, r2);
    EXPECT_EQ(r2.irregular_lines, (std::vector<std::size_t>{12}));
}

TEST(LogFormat, SplitGivesSegmentsOnOneGridPeriodAtTheirTrueTimes) {
    std::vector<double> steps(30, 0.005);
    steps[10] = 0.030;  // gap before line 12
    steps[20] = 0.500;  // gap before line 22
    steps[29] = 0.100;  // gap before line 31, the last row: a segment of one row
    const auto names = LogColumnNames::numbered(2);
    LogReadSettings settings;
    settings.on_gap = GapPolicy::Split;
    LogReadReport report;
    const std::vector<CsvTable> tables = parse_formatted_log_segments(clock_rows(steps), "g.csv", kPendubotLike, names, settings, report);
    ASSERT_EQ(tables.size(), 4u);
    ASSERT_EQ(report.segments.size(), 4u);
    EXPECT_EQ(report.gap_lines, (std::vector<std::size_t>{12, 22, 31}));
    const std::size_t first[] = {1, 12, 22, 31}, last[] = {11, 21, 30, 31}, samples[] = {11, 10, 9, 1};
    const double start[] = {10.0, 10.08, 10.625, 10.765};
    for (std::size_t s = 0; s < 4; ++s) {
        const LogSegment& g = report.segments[s];
        EXPECT_EQ(g.first_line, first[s]) << s;
        EXPECT_EQ(g.last_line, last[s]) << s;
        EXPECT_EQ(g.rows, last[s] - first[s] + 1) << s;
        EXPECT_EQ(g.samples, samples[s]) << s;
        EXPECT_EQ(tables[s].rows(), samples[s]) << s;
        EXPECT_NEAR(g.start, start[s], 1e-9) << s;
        EXPECT_NEAR(g.duration, 0.005 * static_cast<double>(samples[s] - 1), 1e-9) << s;
        // Each grid starts at its segment's first row, one period for all (gaps excluded from the mean).
        const auto& t = tables[s].column("t");
        for (std::size_t k = 0; k < t.size(); ++k) {
            EXPECT_NEAR(t[k], start[s] + 0.005 * static_cast<double>(k), 1e-9) << s;
            EXPECT_NEAR(tables[s].column("q1")[k], std::sin(t[k]), 2e-6) << s;  // grid points are the sample times
        }
        EXPECT_EQ(tables[s].source(), "g.csv (lines " + std::to_string(first[s]) + "-" + std::to_string(last[s]) + ")");
    }
    EXPECT_EQ(report.segments[1].describe(), "lines 12-21: 0.045 s, 10 samples");
    EXPECT_NEAR(report.grid_period, 0.005, 1e-9);
    EXPECT_EQ(report.samples, 31u);
    EXPECT_NE(report.summary().find("3 gaps split the log into 4 segments (first at line 12: 30 ms)"), std::string::npos) << report.summary();
    // One table cannot hold segments: the single-table reader says so at the first gap.
    LogReadReport again;
    EXPECT_EQ(error_of([&] { parse_formatted_log(clock_rows(steps), "g.csv", kPendubotLike, names, settings, again); }),
              "g.csv:12: time step 30 ms is a gap and --on-gap split cuts the log into 4 segments, but this reader takes one table");
    // Without gaps, split is the single table of the other policies.
    LogReadReport whole, plain;
    const std::vector<double> regular(30, 0.005);
    const std::vector<CsvTable> one = parse_formatted_log_segments(clock_rows(regular), "r.csv", kPendubotLike, names, settings, whole);
    const CsvTable reference = parse_formatted_log(clock_rows(regular), "r.csv", kPendubotLike, names, {}, plain);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(one.front().column("q1"), reference.column("q1"));
    EXPECT_EQ(one.front().source(), "r.csv");
}

}  // namespace

namespace {

TEST(LogFormat, GridPeriodCanBeImposed) {
    // A validation log resampled onto the identification log's period (diagnose --validate needs one period).
    std::vector<double> steps(40, 0.005);
    LogReadSettings settings;
    settings.period = 0.004;
    LogReadReport report;
    const CsvTable t = parse_formatted_log(clock_rows(steps), "p.csv", kPendubotLike, LogColumnNames::numbered(2), settings, report);
    EXPECT_EQ(report.grid_period, 0.004);
    EXPECT_EQ(t.rows(), 51u);  // 0.2 s / 4 ms + 1
    EXPECT_NEAR(t.column("q1")[25], std::sin(10.0 + 0.1), 1e-6);
}

}  // namespace

namespace {

TEST(LogFormat, ValuesThatOverflowOnceScaledAreBadRows) {
    const LogFormat f = parse_log_format("header: false\ntime: {column: 1}\npositions: [2]\ncurrents: [3]\ngains: [10]\n", "o.yaml");
    LogReadReport report;
    EXPECT_EQ(error_of([&] { parse_formatted_log("1,0,1\n2,0,1e308\n3,0,1\n", "o.csv", f, LogColumnNames::numbered(1), {}, report); }),
              "o.csv:2: column 3 (currents[0]): 1e308 times the gain or scale 10 is not finite (--skip-bad-rows skips such rows and reports them)");
    // Times are bounded like every other value (issue 36: a corrupt stamp of 1e154 s is no time), so the span is always finite.
    EXPECT_EQ(error_of([&] { parse_formatted_log("-1e308,0,1\n1e308,0,1\n", "o.csv", f, LogColumnNames::numbered(1), {}, report); }),
              "o.csv:1: column 1 (time): value -1e+308 is beyond +-1e30, which no measurement is (an outlier? its square would overflow the "
              "identification) (--skip-bad-rows skips such rows and reports them)");
}

}  // namespace

namespace {

TEST(LogFormat, MeasuredVelocitiesReachTheLogColumns) {
    const LogFormat f = parse_log_format("header: false\ntime: {column: 1}\npositions: [2, 3]\nvelocities: [4, null]\ntorques: [5, 6]\n", "v.yaml");
    std::string text;
    for (int k = 0; k < 30; ++k) text += std::to_string(0.01 * k) + ",1,2," + std::to_string(0.5 * k) + ",4,5\n";
    LogReadReport report;
    const CsvTable t = parse_formatted_log(text, "v.csv", f, LogColumnNames::numbered(2), {}, report);
    const auto robot = jacobid::robot::parse_robot_description("model: planar2r\n", "r.yaml");
    const auto log = jacobid::identify::log_columns(t, robot, "t", 0.01);
    ASSERT_EQ(log.qd.size(), 2u);
    ASSERT_NE(log.qd[0], nullptr);
    EXPECT_EQ(log.qd[1], nullptr);  // velocities[1]: null, not logged
    EXPECT_NEAR((*log.qd[0])[7], 3.5, 1e-9);
    EXPECT_NEAR((*log.tau[1])[7], 5.0, 1e-12);
}

}  // namespace
