// SPDX-License-Identifier: MIT
// identify --torque-delay auto on simulated 2R logs whose torque channel is misaligned by a known amount:
// half a sample early (built exactly, without interpolation: a 2 kHz simulation whose 1 kHz rows take the
// torque of the NEXT 2 kHz row) and 2 ms late (the simulator's torque_delay effect). Expected values are
// the simulation's truth (the paper's Table II) and the offset we built in.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "identify/plan/log_columns.hpp"
#include "identify/friction/torque_delay.hpp"
#include "identify/validation/validation.hpp"
#include "io/csv_table.hpp"
#include "io/time_axis.hpp"
#include "robot/robot_description.hpp"
#include "run_command.hpp"
#include "simulated_log.hpp"
#include "scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string path(const std::string& name) { return (jacobid::test::scratch_directory() / name).string(); }

jacobid::test::CommandResult jacobid_cli(const std::string& args) { return jacobid::test::run_command(std::string(JACOBID_EXECUTABLE) + " " + args); }

const char* kRobot = "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100}\n";
const char* kNoise = " --encoder-counts 65536 --torque-noise 0.05,0.01 --seed 1 --duration 60";

std::string robot() {
    std::ofstream(path("robot.yaml")) << kRobot;
    return path("robot.yaml");
}

// A 1 kHz log whose torques lead the positions by half a sample: every second row of a 2 kHz simulation
// (controller at 2 kHz too, so that consecutive rows hold different torques),
// each with the torques of the row after it.
std::string half_sample_lead_log() {
    const std::string fine = path("fine.csv"), lead = path("lead.csv");
    if (fs::exists(lead)) return lead;
    const auto r = jacobid::test::simulated_log(fine, "--quiet --robot " + robot() + " --rate 2000 --control-rate 2000" + kNoise);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(fine);
    std::string header;
    std::getline(in, header);
    std::vector<std::string> rows;
    for (std::string line; std::getline(in, line);) rows.push_back(line);
    // Columns t,q1,q2,tau1,tau2 (checked): keep t,q of row 2k and tau of row 2k+1.
    EXPECT_EQ(header.rfind("t,q1,q2,tau1,tau2", 0), 0u) << header;
    const auto split = [](const std::string& s) {
        std::vector<std::string> cells;
        std::stringstream ss(s);
        for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
        return cells;
    };
    std::ofstream out(lead);
    out << "t,q1,q2,tau1,tau2\n";
    for (std::size_t k = 0; k + 1 < rows.size(); k += 2) {
        const auto now = split(rows[k]), next = split(rows[k + 1]);
        out << now[0] << ',' << now[1] << ',' << now[2] << ',' << next[3] << ',' << next[4] << '\n';
    }
    return lead;
}

json identify(const std::string& log, const std::string& args) {
    const auto r = jacobid_cli("identify --quiet --robot " + robot() + " --in " + log + " --format json " + args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(r.out);
}

double error_percent(const json& j, const std::string& name, double truth) { return 100.0 * (j["parameters"][name]["value"].get<double>() - truth) / truth; }

void expect_friction_within(const json& j, double percent, const std::string& what) {
    const std::pair<const char*, double> truth[] = {{"FV1", 0.248}, {"FC1", 0.431}, {"FV2", 0.0144}, {"FC2", 0.1268}};
    for (const auto& [name, value] : truth) EXPECT_LT(std::abs(error_percent(j, name, value)), percent) << what << " " << name;
}

}  // namespace

TEST(TorqueDelay, HalfSampleLeadIsEstimatedCompensatedAndReported) {
    const std::string log = half_sample_lead_log();
    // Uncompensated, the lead biases friction (this is what the estimate has to remove).
    const json off = identify(log, "--torque-delay 0");
    EXPECT_GT(std::abs(error_percent(off, "FV1", 0.248)), 2.0) << off["parameters"].dump();
    for (const char* method : {"jacobi", "butterworth"}) {
        const json j = identify(log, std::string("--method ") + method);
        const json& d = j["torque_delay"];
        EXPECT_NEAR(d["seconds"].get<double>(), -0.0005, 0.00005) << method << " " << d.dump();
        EXPECT_TRUE(d["compensated"].get<bool>()) << method;
        EXPECT_TRUE(d["estimated"].get<bool>());
        EXPECT_GT(d["std"].get<double>(), 0.0);
        EXPECT_LT(d["std"].get<double>(), 0.00005) << method;
        expect_friction_within(j, 0.5, method);
    }
}

TEST(TorqueDelay, TwoMillisecondsLateAndAGivenDelay) {
    const std::string log = path("late.csv");
    const auto r = jacobid::test::simulated_log(log, "--quiet --robot " + robot() + kNoise + " --effect torque_delay:value=0.002");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = identify(log, "");
    EXPECT_NEAR(j["torque_delay"]["seconds"].get<double>(), 0.002, 0.00005) << j["torque_delay"].dump();
    expect_friction_within(j, 0.5, "auto");
    const json given = identify(log, "--torque-delay 0.002");
    EXPECT_FALSE(given["torque_delay"]["estimated"].get<bool>());
    EXPECT_DOUBLE_EQ(given["torque_delay"]["applied_seconds"].get<double>(), 0.002);
    expect_friction_within(given, 0.5, "given");
    const auto bad = jacobid_cli("identify --robot " + robot() + " --in " + log + " --torque-delay 2ms");
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("--torque-delay '2ms'"), std::string::npos) << bad.err;
}

namespace {

// A simulated 2R log read in-process: the model, the table and the log's columns.
struct LateLog {
    jacobid::robot::RobotDescription description;
    std::unique_ptr<jacobid::robot::RobotModel> model;
    jacobid::io::CsvTable table;
    jacobid::identify::LogColumns columns;
};
std::unique_ptr<LateLog> simulated_columns(const std::string& name, const std::string& args) {
    const std::string log = path(name);
    const auto r = jacobid::test::simulated_log(log, "--quiet --robot " + robot() + args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    auto l = std::make_unique<LateLog>();
    l->description = jacobid::robot::load_robot_description(robot());
    l->model = jacobid::robot::make_robot_model(l->description);
    l->table = jacobid::io::read_csv(log);
    l->columns = jacobid::identify::log_columns(l->table, l->description, "t", jacobid::io::kDefaultTimeTolerance);
    return l;
}

// The same 2R log, 2 ms late.
std::unique_ptr<LateLog> late_log(const std::string& name) { return simulated_columns(name, std::string(kNoise) + " --effect torque_delay:value=0.002"); }

}  // namespace

// Issue 35: on logs with no delay the reported std must describe the estimates' spread, or the 3-std test
// compensates delays that are not there (the independent-rows std was 2.1 x too small on excite's designs: 17
// of 100 runs compensated). 40 logs of one motion with fresh torque noise, 10 x the other tests' so that the
// noise, not the model's own error (the same on every run of one motion: with 0.05,0.01 the estimates sit
// 3 us off and spread less than either std), decides the spread. Reference: the spread of the estimates
// around the truth, 0, known to about 11 % from 40 runs; measured 1.04 x the std (the independent-rows std:
// 2.0 x, 6 of 40 compensated). A 3-std test fires on 0.3 % of honest runs: at most 2 of 40.
TEST(TorqueDelay, StdMatchesTheSpreadOnDelayFreeLogs) {
    const int runs = 40;
    std::vector<double> delays;
    double variance = 0.0;
    int compensated = 0;
    for (int k = 1; k <= runs; ++k) {
        const auto log = simulated_columns("free" + std::to_string(k) + ".csv",
                                           " --encoder-counts 262144 --torque-noise 0.5,0.1 --seed 1 --duration 20 --noise-seed " + std::to_string(k));
        jacobid::identify::SolveOptions wls;  // identify's default weighting, as in the figures above
        wls.weighted = true;
        const auto e = jacobid::identify::estimate_torque_delay(*log->model, log->columns, {}, wls);
        ASSERT_TRUE(std::isfinite(e.std_dev)) << k;
        EXPECT_GT(e.std_lags, 0) << "the rows were kept: the std carries their correlation";
        delays.push_back(e.delay);
        variance += e.std_dev * e.std_dev / runs;
        compensated += e.compensated ? 1 : 0;
    }
    double spread = 0.0;
    for (const double d : delays) spread += d * d / runs;  // around the truth, 0
    const double ratio = std::sqrt(spread / variance);
    EXPECT_GT(ratio, 0.8);
    EXPECT_LT(ratio, 1.3);
    EXPECT_LE(compensated, 2);
}

// Long logs are searched on their beginning (TorqueDelaySettings::max_samples): the same offset comes out.
TEST(TorqueDelay, LongLogsAreSearchedOnTheirFirstSamples) {
    const auto late = late_log("late_lib.csv");
    const auto& model = late->model;
    const auto& columns = late->columns;
    jacobid::identify::TorqueDelaySettings settings;
    settings.max_samples = 20000;
    const auto e = jacobid::identify::estimate_torque_delay(*model, columns, {}, {}, settings);
    EXPECT_EQ(e.samples_used, 20000u);
    EXPECT_NEAR(e.delay, 0.002, 0.0001);
    EXPECT_TRUE(e.compensated);
}

// The search's shifted identifications reuse the first one's rows with the filtered torque read i samples
// later (the filters are linear and time-invariant). Reference: the shifted torque filtered itself, i.e. the
// pipeline run again on shift_torques' log with the first run's plan, as the search did before. They differ
// only by the |i| samples at one end of the record, which the shift holds at the end value: those reach the
// kept rows through the filters' cropped end transients (decayed to ~1e-3), so RSS agrees to ~5e-7 relative
// (Jacobi) and ~4e-6 (Butterworth: F_q pads the record from its end values) here, where a shift off by one
// sample would change it by a factor of 10 to 100.
TEST(TorqueDelay, ShiftedRowsEqualTheShiftedTorqueFilteredAgain) {
    const auto late = late_log("late_rows.csv");
    const auto& model = late->model;
    const auto& columns = late->columns;
    for (const auto method : {jacobid::identify::Method::Jacobi, jacobid::identify::Method::Butterworth}) {
        jacobid::identify::PipelineSettings settings;
        settings.method = method;
        settings.residual_lags = 0;
        settings.plot_rows = 0;
        const auto e = jacobid::identify::estimate_torque_delay(*model, columns, settings, {});
        ASSERT_GE(e.grid.size(), 4u);
        const auto first = jacobid::identify::run_pipeline(*model, columns, settings);
        const auto imposed = jacobid::identify::validation_settings(settings, first.info);
        for (std::size_t g = 0; g < e.grid.size(); ++g) {
            if (e.grid[g] == 0.0) continue;
            const auto shifted = jacobid::identify::shift_torques(columns, e.grid[g]);
            const auto again = jacobid::identify::run_pipeline(*model, shifted.log, imposed);
            const double rss = std::pow(jacobid::identify::solve_least_squares(again.factors, model->parameter_names(), {}).residual_norm, 2);
            EXPECT_NEAR(e.rss[g], rss, 1e-5 * rss) << jacobid::identify::to_string(method) << " shift " << e.grid[g];
        }
        EXPECT_NEAR(e.delay, 0.002, 0.0001);
    }
}

namespace {

// An estimate without curvature at its minimum (at the edge of the search range: a 1 s PUMA log did it)
// has no std: the text says so in words instead of printing "std inf ms" (issue 20: no non-finite value
// in a result; the JSON writes null).
TEST(TorqueDelay, AnUnknownStdIsSaidInWordsNotPrintedAsInf) {
    jacobid::identify::TorqueDelayResult r;
    r.estimate.delay = -0.005;
    r.estimate.std_dev = std::numeric_limits<double>::infinity();
    r.estimate.at_bound = true;
    const std::string text = jacobid::identify::describe(r);
    EXPECT_NE(text.find("torque delay -5.000 ms (std unknown, "), std::string::npos) << text;
    EXPECT_EQ(text.find("inf"), std::string::npos) << text;
    r.estimate.std_dev = 0.0004;
    EXPECT_NE(jacobid::identify::describe(r).find("(std 0.400 ms, "), std::string::npos) << jacobid::identify::describe(r);
}

// Aligned in place (LogColumns::own_tau: identify's own table, one method) or into a copy, the torques are
// the same values: both against linear interpolation written out here, for leads and lags of whole and
// fractional samples, ends held.
TEST(TorqueDelay, TorquesAlignedInPlaceEqualTheCopy) {
    const std::size_t n = 50;
    std::vector<std::vector<double>> q = {std::vector<double>(n, 0.0)}, taus = {std::vector<double>(n)};
    std::vector<double>& tau = taus.front();
    for (std::size_t k = 0; k < n; ++k) tau[k] = std::sin(0.3 * static_cast<double>(k)) + 0.01 * static_cast<double>(k * k);
    const double period = 1e-3;
    for (const double shift : {0.37, -0.37, 1.0, -1.6, 2.5, -3.0}) {
        SCOPED_TRACE(shift);
        std::vector<double> expected(n);
        for (std::size_t k = 0; k < n; ++k) {
            const double at = static_cast<double>(k) + shift;
            const double i = std::floor(at);
            expected[k] = at <= 0.0 ? tau.front() : i + 1 >= static_cast<double>(n) ? tau.back()
                                                                                     : (1.0 - (at - i)) * tau[static_cast<std::size_t>(i)] + (at - i) * tau[static_cast<std::size_t>(i) + 1];
        }
        const jacobid::identify::LogColumns log = jacobid::identify::log_columns(q, taus, period, "test");
        const auto copied = jacobid::identify::shift_torques(log, shift * period);
        std::vector<double> owned_tau = tau;
        jacobid::identify::LogColumns owned = log;
        owned.tau = {&owned_tau};
        owned.own_tau = {&owned_tau};
        const auto in_place = jacobid::identify::shift_torques(owned, shift * period);
        EXPECT_TRUE(in_place.tau.empty()) << "no copy";
        EXPECT_TRUE(in_place.log.own_tau.empty()) << "the view never aligns them again";
        EXPECT_EQ(in_place.log.tau.front(), &owned_tau);
        for (std::size_t k = 0; k < n; ++k) {
            EXPECT_NEAR((*copied.log.tau.front())[k], expected[k], 1e-12) << k;
            EXPECT_EQ(owned_tau[k], (*copied.log.tau.front())[k]) << k;
        }
    }
}

// A view whose torques are aligned by d (LogColumns::tau_aligned_by) is aligned by only what is left of a
// later delay: d again is the view itself (the first piece of a long log is aligned before the smoothing
// choice, then read by the pipeline, which applies the same delay to every piece), d2 shifts it by d2 - d.
TEST(TorqueDelay, TorquesAlreadyAlignedAreShiftedOnlyByWhatIsLeft) {
    const std::size_t n = 40;
    std::vector<std::vector<double>> q = {std::vector<double>(n, 0.0)}, taus = {std::vector<double>(n)};
    for (std::size_t k = 0; k < n; ++k) taus.front()[k] = std::cos(0.2 * static_cast<double>(k)) + 0.05 * static_cast<double>(k);
    const double period = 1e-3;
    const jacobid::identify::LogColumns log = jacobid::identify::log_columns(q, taus, period, "test");
    const auto aligned = jacobid::identify::shift_torques(log, 0.5 * period);
    EXPECT_EQ(aligned.log.tau_aligned_by, 0.5 * period);
    const auto again = jacobid::identify::shift_torques(aligned.log, 0.5 * period);
    EXPECT_TRUE(again.tau.empty()) << "no second copy";
    EXPECT_EQ(again.log.tau.front(), aligned.log.tau.front()) << "no second shift";
    const auto further = jacobid::identify::shift_torques(aligned.log, 1.5 * period);
    const std::vector<double>& a = *aligned.log.tau.front();
    for (std::size_t k = 0; k + 1 < n; ++k) EXPECT_NEAR((*further.log.tau.front())[k], a[k + 1], 1e-12) << k << ": one more whole sample";
    EXPECT_EQ((*further.log.tau.front())[n - 1], a[n - 1]) << "end held";
}

}  // namespace
