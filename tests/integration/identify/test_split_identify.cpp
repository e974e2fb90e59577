// SPDX-License-Identifier: MIT
// --on-gap split (issue 13) on a simulated planar 2R log written as a raw log with rows cut out: identify
// finds the truth as from the whole log, its result is exactly the least squares of the segments' own
// equations stacked by hand (no differentiator window or filter straddles the gap), a segment too short
// for the windows is reported and not silently dropped, --validate is split too; differentiate writes each
// segment on its own with a segment column; diagnose refuses split; the error policy names the gap's line.
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "identify/solve/least_squares.hpp"
#include "identify/plan/log_columns.hpp"
#include "identify/pipeline/pipeline.hpp"
#include "identify/pipeline/segmented_pipeline.hpp"
#include "io/log_format.hpp"
#include "io/time_axis.hpp"
#include "robot/robot_description.hpp"
#include "run_command.hpp"
#include "simulated_log.hpp"
#include "scratch_directory.hpp"
#include "stacked_rows.hpp"

namespace {

using nlohmann::json;
using namespace jacobid;

std::string path(const std::string& name) { return (test::scratch_directory() / name).string(); }
test::CommandResult jacobid_cli(const std::string& args) { return test::run_command(std::string(JACOBID_EXECUTABLE) + " " + args); }

// The simulated log (t,q1,q2,tau1,tau2, 60 s at 1 kHz), then copies without the rows whose time lies in
// one of `cuts` ([from, to) in s), as a robot's logger would leave them.
std::string log_without(const std::string& name, const std::vector<std::pair<double, double>>& cuts) {
    const std::string full = path("split.csv");
    if (!std::ifstream(full)) {
        std::ofstream(path("robot.yaml")) << "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100}\n";
        std::ofstream(path("format.yaml")) << "header: true\ntime: {column: t}\npositions: [q1, q2]\ntorques: [tau1, tau2]\n";
        const auto r = test::simulated_log(full, "--quiet --robot " + path("robot.yaml") + " --duration 60 --encoder-counts 65536 --torque-noise 0.05,0.01 --seed 1");
        EXPECT_EQ(r.exit_code, 0) << r.err;
    }
    std::ifstream in(full);
    std::ofstream out(path(name));
    std::string line;
    std::getline(in, line);
    out << line << '\n';
    while (std::getline(in, line)) {
        const double t = std::stod(line.substr(0, line.find(',')));
        bool cut = false;
        for (const auto& [from, to] : cuts) cut = cut || (t >= from - 1e-9 && t < to - 1e-9);
        if (!cut) out << line << '\n';
    }
    return path(name);
}

const std::vector<std::pair<double, double>> kGap{{25.0, 27.0}};                   // rows 25001-27000 of the file cut
const std::vector<std::pair<double, double>> kGapAndShort{{25.0, 27.0}, {57.5, 59.7}};  // and a 0.3 s piece left at the end

std::string split_args(const std::string& log) {
    return "identify --quiet --robot " + path("robot.yaml") + " --in " + log + " --log-format " + path("format.yaml") + " --torque-delay 0";
}

json run_json(const std::string& args) {
    const auto r = jacobid_cli(args + " --format json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(r.out.empty() ? "{}" : r.out);
}

double value(const json& j, const std::string& name) { return j["methods"]["jacobi"]["parameters"][name]["value"].get<double>(); }

const std::pair<const char*, double> kTruth[] = {{"ZZ1R", 3.496}, {"FV1", 0.248}, {"FC1", 0.431}, {"ZZ2", 0.059}, {"MX2", 0.124}, {"FC2", 0.1268}};

TEST(SplitIdentify, FindsTheTruthAsTheWholeLogDoes) {
    const std::string gap = log_without("gap.csv", kGap);
    const json whole = run_json("identify --quiet --robot " + path("robot.yaml") + " --in " + path("split.csv") + " --torque-delay 0");
    const json split = run_json(split_args(gap) + " --on-gap split");
    for (const auto& [name, truth] : kTruth) {
        EXPECT_NEAR(value(whole, name), truth, 0.01 * truth) << "whole log " << name;  // the reference the split run must match
        EXPECT_NEAR(value(split, name), truth, 0.01 * truth) << "split " << name;
    }
    // The segments: lines of the file (header = line 1), durations, samples, both used.
    ASSERT_EQ(split["segments"].size(), 2u) << split.dump(1);
    const json& s1 = split["segments"][0];
    const json& s2 = split["segments"][1];
    EXPECT_EQ(s1["first_line"], 2);
    EXPECT_EQ(s1["last_line"], 25001);
    EXPECT_EQ(s1["samples"], 25000);
    EXPECT_NEAR(s1["duration_s"].get<double>(), 24.999, 1e-9);
    EXPECT_EQ(s2["first_line"], 25002);
    EXPECT_EQ(s2["last_line"], 58002);
    EXPECT_EQ(s2["samples"], 33001);
    EXPECT_TRUE(s1["used"].get<bool>() && s2["used"].get<bool>());
    EXPECT_EQ(s1["why"], "");
    const auto text = jacobid_cli(split_args(gap) + " --on-gap split");
    EXPECT_NE(text.out.find("Jacobi segments: 2 of 2 used (--on-gap split)"), std::string::npos) << text.out;
}

TEST(SplitIdentify, EqualsTheSegmentsEquationsStackedByHand) {
    const std::string gap = log_without("gap.csv", kGap);
    const robot::RobotDescription robot = robot::load_robot_description(path("robot.yaml"));
    const auto model = robot::make_robot_model(robot);
    io::LogReadSettings settings;
    settings.on_gap = io::GapPolicy::Split;
    io::LogReadReport report;
    const std::vector<io::CsvTable> tables = io::read_formatted_log_segments(gap, io::load_log_format(path("format.yaml")),
                                                                             io::LogColumnNames::numbered(2), settings, report);
    ASSERT_EQ(tables.size(), 2u);
    std::vector<identify::LogColumns> segments;
    for (const auto& t : tables) segments.push_back(identify::log_columns(t, robot, "t", io::kDefaultTimeTolerance));
    const identify::SegmentPlan plan = identify::plan_segments(segments, identify::PipelineSettings{});
    EXPECT_EQ(plan.reference, 1u);  // the longer segment resolves the automatic choices
    const identify::SegmentedOutput merged = identify::run_segmented_pipeline(*model, segments, plan, 0.0);
    ASSERT_EQ(merged.used_count, 2u);
    const std::vector<std::string> names = model->parameter_names();
    const identify::LsSolution split = identify::solve_least_squares(merged.merged.factors, names);

    // By hand: each segment's rows with the same fixed settings, all joints and segments in one dense system.
    const int c = model->parameter_count();
    const test::StackedSystem stacked = test::stack_rows(*model, segments, plan.fixed);
    EXPECT_GT(stacked.rows_per_piece[0], 500u);
    EXPECT_GT(stacked.rows_per_piece[1], 500u);
    const Eigen::VectorXd x = stacked.solve();
    EXPECT_EQ(split.equations, static_cast<std::size_t>(stacked.w.rows()));
    for (int p = 0; p < c; ++p) EXPECT_NEAR(split.x[p], x[p], 1e-9 * std::abs(x[p])) << names[static_cast<std::size_t>(p)];

    // The command gives the same numbers (its JSON keeps every digit) with ordinary LS, as computed by hand
    // (its default is WLS).
    const json cli = run_json(split_args(gap) + " --on-gap split --weighting ols");
    for (int p = 0; p < c; ++p) EXPECT_NEAR(value(cli, names[static_cast<std::size_t>(p)]), x[p], 1e-9 * std::abs(x[p])) << names[static_cast<std::size_t>(p)];
}

TEST(SplitIdentify, ErrorPolicyNamesTheGapByFileAndLine) {
    const std::string gap = log_without("gap.csv", kGap);
    const auto r = jacobid_cli(split_args(gap));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(gap + ":25002: time step 2001 ms after line 25001 is a gap (longer than --max-gap 3 ms)"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--on-gap split cuts the log there"), std::string::npos) << r.err;
}

TEST(SplitIdentify, TooShortSegmentIsReportedNotDropped) {
    const std::string log = log_without("short.csv", kGapAndShort);
    const auto r = jacobid_cli(split_args(log) + " --on-gap split --format json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    ASSERT_EQ(j["segments"].size(), 3u) << j.dump(1);
    EXPECT_TRUE(j["segments"][0]["used"].get<bool>());
    EXPECT_TRUE(j["segments"][1]["used"].get<bool>());
    const json& last = j["segments"][2];
    EXPECT_FALSE(last["used"].get<bool>());
    EXPECT_EQ(last["first_line"], 55502);
    EXPECT_EQ(last["samples"], 301);
    EXPECT_NE(last["why"].get<std::string>().find("too short"), std::string::npos) << last["why"];
    EXPECT_NE(r.err.find("segment 3 (lines 55502-55802: 0.3 s, 301 samples) not used: "), std::string::npos) << r.err;
    for (const auto& [name, truth] : kTruth) EXPECT_NEAR(value(j, name), truth, 0.01 * truth) << name;
    const auto text = jacobid_cli(split_args(log) + " --on-gap split");
    EXPECT_NE(text.out.find("Jacobi segments: 2 of 3 used (--on-gap split)\n  not used: lines 55502-55802 (0.3 s, 301 samples): "), std::string::npos)
        << text.out;
    // Only pieces too short for the windows: an error, with each one's reason.
    const std::string pieces = log_without("pieces.csv", {{0.3, 10.0}, {10.3, 20.0}, {20.3, 60.1}});
    const auto none = jacobid_cli(split_args(pieces) + " --on-gap split");
    EXPECT_EQ(none.exit_code, 2);
    EXPECT_NE(none.err.find("--on-gap split: no segment is usable; the longest of the 3: "), std::string::npos) << none.err;
}

// A lone row between two gaps is a segment of one row: reported unused, never the end of the run; and
// differentiate, whose first segment may be that row, takes the grid's period.
TEST(SplitIdentify, OneRowSegmentIsReportedNotFatal) {
    const std::string log = log_without("lone.csv", {{25.0, 27.0}, {27.001, 29.0}});  // the row at t = 27.000 s stands alone
    const auto r = jacobid_cli(split_args(log) + " --on-gap split --format json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    ASSERT_EQ(j["segments"].size(), 3u) << j.dump(1);
    EXPECT_EQ(j["segments"][1]["samples"], 1);
    EXPECT_FALSE(j["segments"][1]["used"].get<bool>());
    for (const auto& [name, truth] : kTruth) EXPECT_NEAR(value(j, name), truth, 0.01 * truth) << name;
    const std::string first = log_without("lone_first.csv", {{0.001, 2.0}});  // the row at t = 0 alone, then a gap
    const auto d = jacobid_cli("differentiate --log-format " + path("format.yaml") + " --on-gap split --in " + first +
                               " --columns q1 --orders 1 --window 0.3 -o -");
    EXPECT_EQ(d.exit_code, 0) << d.err;
    EXPECT_NE(d.err.find("segment 1"), std::string::npos) << d.err;
}

// Two runs an hour apart: the whole span would be a 3.6 million sample grid; split never builds it.
TEST(SplitIdentify, RunsFarApartAreSplitWithoutAGridOverTheGap) {
    const std::string log = path("hour.csv");
    {
        std::ifstream in(log_without("hour_src.csv", {}));
        std::ofstream out(log);
        std::string line;
        std::getline(in, line);
        out << line << '\n';
        while (std::getline(in, line)) {
            const std::size_t comma = line.find(',');
            const double t = std::stod(line.substr(0, comma));
            if (t >= 25.0 && t < 27.0) continue;
            out << fmt::format("{:.6f}", t >= 27.0 ? t + 3600.0 : t) << line.substr(comma) << '\n';
        }
    }
    const auto r = jacobid_cli(split_args(log) + " --on-gap split --format json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j["segments"].size(), 2u);
    for (const auto& [name, truth] : kTruth) EXPECT_NEAR(value(j, name), truth, 0.01 * truth) << name;
}

TEST(SplitIdentify, ValidationLogIsSplitToo) {
    const std::string gap = log_without("gap.csv", kGap), log = log_without("short.csv", kGapAndShort);
    const json j = run_json(split_args(gap) + " --on-gap split --validate " + log);
    ASSERT_EQ(j["validation_segments"].size(), 3u) << j.dump(1);
    EXPECT_FALSE(j["validation_segments"][2]["used"].get<bool>());
    // The pooled figures: the samples of both used segments, errors of the same size as on the whole log.
    const json whole = run_json("identify --quiet --robot " + path("robot.yaml") + " --in " + path("split.csv") + " --torque-delay 0 --validate " +
                                path("split.csv"));
    const json& v = j["validation"];
    const json& w = whole["validation"];
    EXPECT_GT(v["samples"].get<double>(), 0.8 * w["samples"].get<double>());
    EXPECT_LT(v["samples"].get<double>(), w["samples"].get<double>());
    EXPECT_LT(v["relative_error"].get<double>(), 1.5 * w["relative_error"].get<double>());
    for (std::size_t k = 0; k < 2; ++k) EXPECT_LT(v["rms_error"][k].get<double>(), 1.5 * w["rms_error"][k].get<double>()) << k;
    // Pooling is exact: validating on the identification log itself gives back its relative error norm (the
    // same segments through the same filters, the residual sums of squares added over the segments).
    const json self = run_json(split_args(gap) + " --on-gap split --validate " + gap);
    EXPECT_NEAR(self["validation"]["relative_error"].get<double>(), self["relative_error_norm"].get<double>(),
                1e-9 * self["relative_error_norm"].get<double>());
    EXPECT_EQ(self["validation"]["samples"].get<std::size_t>() * 2, self["equations"].get<std::size_t>());
}

std::vector<std::vector<double>> read_csv_rows(const std::string& text, std::string& header) {
    std::istringstream in(text);
    std::getline(in, header);
    std::vector<std::vector<double>> rows;
    for (std::string line; std::getline(in, line);) {
        std::vector<double> v;
        std::stringstream s(line);
        for (std::string c; std::getline(s, c, ',');) v.push_back(std::stod(c));
        rows.push_back(v);
    }
    return rows;
}

TEST(SplitIdentify, DifferentiateWritesEachSegmentOnItsOwn) {
    const std::string gap = log_without("gap.csv", kGap);
    const std::string args = " --log-format " + path("format.yaml") + " --columns q1 --orders 1 --window 0.1";
    const auto split = jacobid_cli("differentiate --in " + gap + args + " --on-gap split");
    ASSERT_EQ(split.exit_code, 0) << split.err;
    std::string header;
    const auto rows = read_csv_rows(split.out, header);
    EXPECT_EQ(header, "t,q1_d1,segment");
    // The second segment alone (its rows in a file of their own) gives the very same rows: nothing straddles the gap.
    const std::string second = log_without("second.csv", {{0.0, 27.0}});
    const auto alone = jacobid_cli("differentiate --in " + second + args);
    ASSERT_EQ(alone.exit_code, 0) << alone.err;
    std::string alone_header;
    const auto reference = read_csv_rows(alone.out, alone_header);
    std::vector<std::vector<double>> segment2;
    for (const auto& r : rows) {
        ASSERT_EQ(r.size(), 3u);
        EXPECT_TRUE(r[0] < 25.0 - 0.05 + 1e-9 || r[0] >= 27.0 + 0.05 - 1e-9) << "time " << r[0] << " is in the gap or a window from it";
        EXPECT_EQ(r[2], r[0] < 26.0 ? 1.0 : 2.0);
        if (r[2] == 2.0) segment2.push_back(r);
    }
    ASSERT_EQ(segment2.size(), reference.size());
    for (std::size_t k = 0; k < reference.size(); ++k) {
        EXPECT_DOUBLE_EQ(segment2[k][0], reference[k][0]);
        EXPECT_NEAR(segment2[k][1], reference[k][1], 1e-12) << k;
    }
    EXPECT_NE(split.err.find("rows out"), std::string::npos);
    EXPECT_NE(split.err.find("2 of 2 segments written"), std::string::npos) << split.err;
}

TEST(SplitIdentify, DiagnoseRefusesSplit) {
    const std::string gap = log_without("gap.csv", kGap);
    const auto r = jacobid_cli("diagnose --robot " + path("robot.yaml") + " --in " + gap + " --log-format " + path("format.yaml") + " --on-gap split");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--on-gap split is not supported by diagnose; use interpolate"), std::string::npos) << r.err;
}

}  // namespace
