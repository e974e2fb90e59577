// SPDX-License-Identifier: MIT
// identify --in a.csv --in b.csv (issue 18): several logs identified together, each with its own
// differentiator edges and F_p transients, their equations stacked through the running QR factors. Checked
// against the least squares of both logs' own decimated rows stacked by hand (SVD), against the same two
// logs written as one file with a gap between them (--on-gap split, whose segments are the same equations),
// for independence from the thread count and the --in order, and for the refusals.
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "identify/solve/least_squares.hpp"
#include "identify/plan/log_columns.hpp"
#include "identify/pipeline/pipeline.hpp"
#include "identify/pipeline/segmented_pipeline.hpp"
#include "io/csv_table.hpp"
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

// Two simulated planar 2R logs of different lengths and trajectories (the description's alpha is fixed,
// so no automatic smoothing choice depends on which log is the longest).
struct Logs {
    std::string robot = path("robot.yaml"), a = path("a.csv"), b = path("b.csv");
    Logs() {
        if (std::ifstream(b)) return;
        std::ofstream(robot) << "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100}\n";
        for (const auto& [file, args] : {std::pair<std::string, std::string>{a, "--duration 20 --seed 1 --noise-seed 11"},
                                         std::pair<std::string, std::string>{b, "--duration 12 --seed 2 --noise-seed 12"}}) {
            const auto r = test::simulated_log(file, "--quiet --robot " + robot + " --encoder-counts 65536 --torque-noise 0.05,0.01 " + args);
            EXPECT_EQ(r.exit_code, 0) << r.err;
        }
    }
    std::string identify(const std::string& extra) const { return "identify --quiet --robot " + robot + " --torque-delay 0 " + extra; }
};

json run_json(const std::string& args) {
    const auto r = jacobid_cli(args + " --format json");
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    return json::parse(r.out.empty() ? "{}" : r.out);
}

double value(const json& j, const std::string& name) { return j["methods"]["jacobi"]["parameters"][name]["value"].get<double>(); }

TEST(SeveralLogs, EqualTheLeastSquaresOfBothLogsRowsStackedByHand) {
    const Logs logs;
    const robot::RobotDescription robot = robot::load_robot_description(logs.robot);
    const auto model = robot::make_robot_model(robot);
    const io::CsvTable ta = io::read_csv(logs.a), tb = io::read_csv(logs.b);
    const std::vector<identify::LogColumns> columns = {identify::log_columns(ta, robot, "t", io::kDefaultTimeTolerance),
                                                       identify::log_columns(tb, robot, "t", io::kDefaultTimeTolerance)};
    // The automatic choices of the longest log (a), imposed on both.
    const identify::SegmentPlan plan = identify::plan_segments(columns, identify::PipelineSettings{});
    ASSERT_EQ(plan.reference, 0u);
    const int c = model->parameter_count();
    const test::StackedSystem stacked = test::stack_rows(*model, columns, plan.fixed);
    const std::size_t per_log[2] = {stacked.rows_per_piece[0], stacked.rows_per_piece[1]};
    EXPECT_GT(per_log[1], 300u);
    EXPECT_GT(per_log[0], per_log[1]);
    const Eigen::VectorXd x = stacked.solve();

    const json both = run_json(logs.identify("--in " + logs.a + " --in " + logs.b + " --weighting ols"));
    const std::vector<std::string> names = model->parameter_names();
    for (int p = 0; p < c; ++p) {
        EXPECT_NEAR(value(both, names[static_cast<std::size_t>(p)]), x[p], 1e-10 * std::abs(x[p])) << names[static_cast<std::size_t>(p)];
    }
    // What each log gave, in --in order.
    EXPECT_EQ(both["logs"], json::array({logs.a, logs.b}));
    EXPECT_EQ(both["log"], logs.a + " + " + logs.b);
    const json& pieces = both["methods"]["jacobi"]["segments"];
    ASSERT_EQ(pieces.size(), 2u) << both.dump(1);
    EXPECT_EQ(pieces[0]["log"], logs.a);
    EXPECT_EQ(pieces[1]["log"], logs.b);
    EXPECT_EQ(pieces[0]["rows"], per_log[0]);
    EXPECT_EQ(pieces[1]["rows"], per_log[1]);
    EXPECT_EQ(pieces[0]["samples"], 20001);
    EXPECT_TRUE(pieces[0]["used"].get<bool>() && pieces[1]["used"].get<bool>());
    const auto text = jacobid_cli(logs.identify("--in " + logs.a + " --in " + logs.b));
    // Once (CI's sanitizer stage, 2026-12-06) this output was empty and the run is not reproduced: say why if again.
    EXPECT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find(fmt::format("Jacobi segments: 2 of 2 used\n  {} (20 s, 20001 samples): {} equations per joint", logs.a, per_log[0])),
              std::string::npos)
        << text.out;
}

// The two logs as one file, b after a with a 10 s gap: --on-gap split cuts it into the same two pieces, so the
// default (WLS, joint-HAC std) results must agree too, std included (the file's time axis is shifted, so its
// grid period differs from the logs' in the last digits: agreement to rounding, not bit for bit).
TEST(SeveralLogs, EqualOneFileOfBothLogsSplitAtTheGap) {
    const Logs logs;
    const io::CsvTable ta = io::read_csv(logs.a), tb = io::read_csv(logs.b);
    {
        std::ofstream out(path("joined.csv"));
        out << "t,q1,q2,tau1,tau2\n";
        out.precision(17);
        const auto write = [&](const io::CsvTable& t, double shift) {
            const auto& time = t.column("t");
            for (std::size_t i = 0; i < time.size(); ++i) {
                out << time[i] + shift;
                for (const char* name : {"q1", "q2", "tau1", "tau2"}) out << ',' << t.column(name)[i];
                out << '\n';
            }
        };
        write(ta, 0.0);
        write(tb, 30.0);  // a ends at 20 s, b starts at 30 s
    }
    std::ofstream(path("format.yaml")) << "header: true\ntime: {column: t}\npositions: [q1, q2]\ntorques: [tau1, tau2]\n";
    const json both = run_json(logs.identify("--in " + logs.a + " --in " + logs.b));
    const json split = run_json(logs.identify("--in " + path("joined.csv") + " --log-format " + path("format.yaml") + " --on-gap split"));
    ASSERT_EQ(split["methods"]["jacobi"]["segments"].size(), 2u);
    for (const auto& [name, p] : both["methods"]["jacobi"]["parameters"].items()) {
        const json& q = split["methods"]["jacobi"]["parameters"][name];
        EXPECT_NEAR(p["value"].get<double>(), q["value"].get<double>(), 1e-10 * std::abs(q["value"].get<double>())) << name;
        // The std goes through the long-run variance (differences of lagged sums): agreement to rounding is looser.
        EXPECT_NEAR(p["std"].get<double>(), q["std"].get<double>(), 1e-6 * std::abs(q["std"].get<double>())) << name;
    }
}

TEST(SeveralLogs, NeitherTheThreadCountNorTheOrderChangesTheResult) {
    const Logs logs;
    const std::string ab = "--in " + logs.a + " --in " + logs.b + " --method both";
    const json one = run_json(logs.identify(ab + " --threads 1"));
    const json two = run_json(logs.identify(ab + " --threads 2"));
    const json ba = run_json(logs.identify("--in " + logs.b + " --in " + logs.a + " --method both --threads 2"));
    // One log: its regressor, F_p and QR split over the threads; with alpha: auto, whose candidate model keeps
    // per-call scratch between its regressor and history calls (its rows are then built on one thread: they
    // raced when split, and the result moved by up to 2 % under load).
    const std::string auto_robot = path("robot_auto.yaml");
    std::ofstream(auto_robot) << "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: auto}\n";
    const std::string alone = "identify --quiet --robot " + auto_robot + " --torque-delay 0 --in " + logs.a + " --method both";
    const json alone1 = run_json(alone + " --threads 1");
    const json alone2 = run_json(alone + " --threads 2");
    ASSERT_TRUE(alone1.contains("coulomb_smoothing")) << "alpha auto was not chosen from data";
    for (const char* method : {"jacobi", "butterworth"}) {
        for (const auto& [name, p] : alone1["methods"][method]["parameters"].items()) {
            EXPECT_EQ(p["value"], alone2["methods"][method]["parameters"][name]["value"]) << method << ' ' << name;
            EXPECT_EQ(p["std"], alone2["methods"][method]["parameters"][name]["std"]) << method << ' ' << name;
        }
        for (const auto& [name, p] : one["methods"][method]["parameters"].items()) {
            EXPECT_EQ(p["value"], two["methods"][method]["parameters"][name]["value"]) << method << ' ' << name;  // bit for bit
            const double v = p["value"].get<double>();
            EXPECT_NEAR(ba["methods"][method]["parameters"][name]["value"].get<double>(), v, 1e-10 * std::abs(v)) << method << ' ' << name;
        }
    }
}

TEST(SeveralLogs, ALogTooShortIsReportedAndTheOthersIdentify) {
    const Logs logs;
    {
        const io::CsvTable ta = io::read_csv(logs.a);
        std::ofstream out(path("short.csv"));
        out << "t,q1,q2,tau1,tau2\n";
        out.precision(17);
        for (std::size_t i = 0; i < 200; ++i) {
            out << ta.column("t")[i];
            for (const char* name : {"q1", "q2", "tau1", "tau2"}) out << ',' << ta.column(name)[i];
            out << '\n';
        }
    }
    const auto r = jacobid_cli(logs.identify("--in " + logs.a + " --in " + path("short.csv") + " --in " + logs.b + " --format json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    const json& pieces = j["methods"]["jacobi"]["segments"];
    ASSERT_EQ(pieces.size(), 3u);
    EXPECT_TRUE(pieces[0]["used"].get<bool>());
    EXPECT_FALSE(pieces[1]["used"].get<bool>());
    EXPECT_TRUE(pieces[2]["used"].get<bool>());
    EXPECT_NE(pieces[1]["why"].get<std::string>().find("too short"), std::string::npos) << pieces[1]["why"];
    EXPECT_NE(r.err.find(fmt::format("jacobid identify [jacobi]: {} not used: ", path("short.csv"))), std::string::npos) << r.err;
    // Only logs too short: an error naming them (two different ones: a byte-identical copy is refused as given twice).
    {
        const std::string text = io::read_text_file(path("short.csv"), "log");
        std::ofstream(path("short2.csv")) << text.substr(0, text.rfind('\n', text.size() - 2) + 1);
    }
    const auto none = jacobid_cli(logs.identify("--in " + path("short.csv") + " --in " + path("short2.csv")));
    EXPECT_EQ(none.exit_code, 2);
    EXPECT_NE(none.err.find("--in: no log is usable; the longest of the 2: "), std::string::npos) << none.err;
}

TEST(SeveralLogs, RefusalsNameTheOptionAndTheLog) {
    const Logs logs;
    const std::string ab = "--in " + logs.a + " --in " + logs.b;
    // Another sample period: one plan cannot serve both.
    {
        const io::CsvTable tb = io::read_csv(logs.b);
        std::ofstream out(path("slow.csv"));
        out << "t,q1,q2,tau1,tau2\n";
        out.precision(17);
        for (std::size_t i = 0; i < tb.column("t").size(); i += 2) {
            out << tb.column("t")[i];
            for (const char* name : {"q1", "q2", "tau1", "tau2"}) out << ',' << tb.column(name)[i];
            out << '\n';
        }
    }
    const auto slow = jacobid_cli(logs.identify("--in " + logs.a + " --in " + path("slow.csv")));
    EXPECT_EQ(slow.exit_code, 2);
    EXPECT_NE(slow.err.find(fmt::format("--in {}: sampled every 2 ms, but --in {} every 1 ms", path("slow.csv"), logs.a)), std::string::npos) << slow.err;
    const auto period = jacobid_cli(logs.identify(ab + " --period auto"));
    EXPECT_EQ(period.exit_code, 2);
    EXPECT_NE(period.err.find("--period with 2 --in logs"), std::string::npos) << period.err;
    const auto threads = jacobid_cli(logs.identify(ab + " --threads -1"));
    EXPECT_EQ(threads.exit_code, 2);
    EXPECT_NE(threads.err.find("--threads"), std::string::npos) << threads.err;
    const auto twice = jacobid_cli(logs.identify(ab + " --in " + logs.a));
    EXPECT_EQ(twice.exit_code, 2);
    EXPECT_NE(twice.err.find(fmt::format("--in {}: given twice (--in number 1 and 3)", logs.a)), std::string::npos) << twice.err;
    const auto output = jacobid_cli(logs.identify(ab + " -o " + logs.b));
    EXPECT_EQ(output.exit_code, 2);
    EXPECT_NE(output.err.find("is the input given to --in"), std::string::npos) << output.err;
}

}  // namespace
