// SPDX-License-Identifier: MIT
// jacobid monitor on the real UR10e (issue 40; docs/real-data.md, "Contact monitoring"): the model identified
// from 14harm50sec (identify --export-robot), thresholds from the shared contact-free logs (not the 2.805 kg
// payload run, whose load the model does not know) as examples/07_monitor_ur10e.sh calibrates them.
//  - The push log: a person pushes the standing arm; the reference is the raw log itself, no model: a push
//    is where a joint's torque (current x the README's drive gain) leaves its resting value (the median of
//    the first 1.5 s) by more than 20 N.m. Every such push is reported, starting no later than one sample
//    (11 ms) after that crossing, and nothing else is.
//  - Every contact-free log (identification and validation, moving and static), each with thresholds
//    calibrated on all the others (leave one out): no alarm (with JACOBID_REALDATA_ONE_PER_FAMILY=1, the
//    sanitizer run, the first log only).
// Skips when ../shared/realdata is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "realdata.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using jacobid::test::run_command;

const std::string kJacobid = JACOBID_EXECUTABLE;
// examples/07_monitor_ur10e.sh's calibration (docs/real-data.md, "Break-away and ringing").
const std::string kCalibration = "--false-alarm-rate 1e-4 --margin 0.5 --confirm 2 --standing-time 0.3 --band-margin 0.2,0.2,0.4,0.2,0.2,0.2";
constexpr double kGains[6] = {10.0, 10.6956, 8.4566, 9.0029, 9.48, 10.1232};  // N.m/A, the README's

struct Ur10eFiles {
    fs::path data, format, robot;
    std::vector<fs::path> free;
};

// Identifies the model once per test program; empty data path when the logs are absent.
const Ur10eFiles& setup() {
    static const Ur10eFiles s = [] {
        Ur10eFiles r;
        const fs::path ur = jacobid::test::realdata_dir() / "ur10e";
        if (!fs::exists(ur / "collision" / "ur-20_01_22-push_pose_1.csv")) return r;
        r.data = ur;
        r.format = jacobid::test::log_formats_dir() / "ur10e.yaml";
        for (const char* folder : {"identification", "validation"}) {
            for (const auto& entry : fs::directory_iterator(ur / folder)) {
                const std::string name = entry.path().filename().string();
                if (entry.path().extension() == ".csv" && name.find("Load") == std::string::npos) r.free.push_back(entry.path());
            }
        }
        std::sort(r.free.begin(), r.free.end());
        const std::string description = jacobid::test::write_scratch_file(
            "monitor_ur10e", "ur10e.yaml",
            "model: urdf\nurdf: " + (ur / "ur10e.urdf").string() +
                "\ngravity: [0, 0, -9.81]\nfriction: {coulomb: smooth, alpha: auto, offset: true}\nrotor_inertia: true\n");
        r.robot = jacobid::test::scratch_file("monitor_ur10e", "identified.yaml");
        const auto id = run_command(kJacobid + " identify --robot " + description + " --log-format " + r.format.string() + " --in " +
                                    (ur / "identification" / "ur-20_02_19_14harm50sec.csv").string() + " --export-robot " + r.robot.string() + " --quiet");
        EXPECT_EQ(id.exit_code, 0) << id.err;
        return r;
    }();
    return s;
}

std::string calibrate(const std::vector<fs::path>& logs, const std::string& name) {
    const Ur10eFiles& s = setup();
    std::string cmd = kJacobid + " monitor calibrate --robot " + s.robot.string() + " --log-format " + s.format.string() + " --out " +
                      jacobid::test::scratch_file("monitor_ur10e", name).string() + " " + kCalibration;
    for (const auto& log : logs) cmd += " --in " + log.string();
    const auto r = run_command(cmd);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return jacobid::test::scratch_file("monitor_ur10e", name).string();
}

nlohmann::json events_of(const fs::path& log, const std::string& monitor) {
    const Ur10eFiles& s = setup();
    const auto r = run_command(kJacobid + " monitor --robot " + s.robot.string() + " --log-format " + s.format.string() + " --monitor " + monitor +
                               " --in " + log.string() + " --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out)["events"];
}

struct Push {
    double crossing = 0.0, end = 0.0;  // robot clock, s
};

// From the raw rows: intervals where some joint's torque is more than 20 N.m from its resting value, merged
// across gaps under 0.5 s.
std::vector<Push> pushes_in(const fs::path& log) {
    std::ifstream in(log);
    std::string line;
    std::vector<double> t;
    std::vector<std::array<double, 6>> tau;
    while (std::getline(in, line)) {
        std::stringstream ss(line);
        std::string cell;
        std::vector<double> v;
        while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
        if (v.size() < 19) continue;
        t.push_back(v[0]);
        std::array<double, 6> row{};
        for (int j = 0; j < 6; ++j) row[static_cast<std::size_t>(j)] = kGains[j] * v[static_cast<std::size_t>(13 + j)];
        tau.push_back(row);
    }
    std::array<double, 6> rest{};
    for (std::size_t j = 0; j < 6; ++j) {
        std::vector<double> first;
        for (std::size_t i = 0; i < t.size() && t[i] < t.front() + 1.5; ++i) first.push_back(tau[i][j]);
        std::nth_element(first.begin(), first.begin() + static_cast<std::ptrdiff_t>(first.size() / 2), first.end());
        rest[j] = first[first.size() / 2];
    }
    std::vector<Push> pushes;
    for (std::size_t i = 0; i < t.size(); ++i) {
        double moved = 0.0;
        for (std::size_t j = 0; j < 6; ++j) moved = std::max(moved, std::abs(tau[i][j] - rest[j]));
        if (moved <= 20.0) continue;
        if (!pushes.empty() && t[i] - pushes.back().end < 0.5) {
            pushes.back().end = t[i];
        } else {
            pushes.push_back({t[i], t[i]});
        }
    }
    return pushes;
}

TEST(MonitorUr10e, EveryPushMovingAJointTorqueBy20NmIsReportedWithItsOnsetAndNothingElse) {
    const Ur10eFiles& s = setup();
    if (s.data.empty()) GTEST_SKIP() << "../shared/realdata/ur10e absent (" << jacobid::test::realdata_dir().string() << ")";
    const fs::path log = s.data / "collision" / "ur-20_01_22-push_pose_1.csv";
    const std::vector<Push> pushes = pushes_in(log);
    ASSERT_GE(pushes.size(), 3u);  // the README: "pushes it several times"
    const nlohmann::json events = events_of(log, calibrate(s.free, "all.yaml"));
    for (const Push& p : pushes) {
        bool reported = false;
        for (const auto& e : events) {
            const double start = e["start"].get<double>(), end = e["end"].get<double>();
            if (start <= p.crossing + 0.011 && end >= p.crossing - 1e-9 && start >= p.crossing - 1.0) reported = true;
        }
        EXPECT_TRUE(reported) << "push crossing 20 N.m at " << p.crossing << " s: " << events.dump(1);
        std::cout << "push: torque 20 N.m from rest at " << p.crossing << " s, until " << p.end << " s\n";
    }
    for (const auto& e : events) {
        const double start = e["start"].get<double>(), end = e["end"].get<double>();
        const bool in_a_push =
            std::any_of(pushes.begin(), pushes.end(), [&](const Push& p) { return start <= p.end + 0.5 && end >= p.crossing - 1.0; });
        EXPECT_TRUE(in_a_push) << "event at " << start << " s outside every push";
        std::cout << "event " << start << " - " << end << " s, joints " << e["joints"].dump() << "\n";
    }
}

TEST(MonitorUr10e, ContactFreeLogsRaiseNoAlarmWithThresholdsCalibratedLeavingThemOut) {
    const Ur10eFiles& s = setup();
    if (s.data.empty()) GTEST_SKIP() << "../shared/realdata/ur10e absent (" << jacobid::test::realdata_dir().string() << ")";
    ASSERT_EQ(s.free.size(), 15u);  // 4 Fourier runs (not the payload run), 6 jointwise, 5 static poses
    for (const fs::path& tested : jacobid::test::every_or_first(s.free)) {
        std::vector<fs::path> others;
        for (const auto& f : s.free) {
            if (f != tested) others.push_back(f);
        }
        const nlohmann::json events = events_of(tested, calibrate(others, "loo.yaml"));
        EXPECT_TRUE(events.empty()) << tested.filename() << ": " << events.dump(1);
    }
}

}  // namespace
