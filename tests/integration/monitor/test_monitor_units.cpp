// SPDX-License-Identifier: MIT
// The host side of jacobid monitor on constructed replays whose answers are known by construction: the
// calibration's quantile against a sorted copy, the standing excess beyond the Coulomb band, the events'
// start, end, joints, peak and median, the confirmation, and the monitor YAML's round trip and refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/errors.hpp"
#include "monitor/calibration.hpp"
#include "monitor/contact_events.hpp"
#include "monitor/monitor_file.hpp"

namespace {

using namespace jacobid::monitor;

// One joint; `values` at 1 kHz, every sample moving unless `standing`.
Replay replay_of(const std::vector<double>& values, bool standing = false, double band = 0.0) {
    Replay r;
    r.external.assign(1, values);
    r.band.assign(1, std::vector<double>(values.size(), standing ? band : 0.0));
    r.standing.assign(1, std::vector<char>(values.size(), standing ? 1 : 0));
    for (std::size_t i = 0; i < values.size(); ++i) {
        r.t.push_back(1e-3 * static_cast<double>(i));
        r.row.push_back(i);
    }
    return r;
}

TEST(MonitorCalibration, ThresholdIsTheUpperQuantileOfTheMagnitudesTimesOnePlusTheMargin) {
    std::mt19937 rng(4);
    std::normal_distribution<double> noise(0.0, 2.0);
    std::vector<double> values(20000);
    for (double& v : values) v = noise(rng);
    std::vector<double> sorted(values.size());
    std::transform(values.begin(), values.end(), sorted.begin(), [](double v) { return std::abs(v); });
    std::sort(sorted.begin(), sorted.end(), std::greater<double>());
    // a = 1e-3 of 20000 samples: 20 may exceed, the 21st largest is the quantile.
    const auto c = calibrate({replay_of(values)}, 1e-3, 0.25);
    EXPECT_DOUBLE_EQ(c[0].thresholds.moving, 1.25 * sorted[20]);
    EXPECT_EQ(c[0].moving_samples, values.size());
    // a = 0: the largest.
    EXPECT_DOUBLE_EQ(calibrate({replay_of(values)}, 0.0, 0.0)[0].thresholds.moving, sorted[0]);
}

TEST(MonitorCalibration, StandingThresholdIsTheExcessBeyondTheBand) {
    // Standing, band 3: values inside the band count as 0 excess; 3.5 is 0.5 beyond it.
    const auto c = calibrate({replay_of({1.0, -2.9, 3.5, -3.2, 0.0}, true, 3.0)}, 0.0, 0.0);
    EXPECT_DOUBLE_EQ(c[0].thresholds.standing, 0.5);
    EXPECT_DOUBLE_EQ(c[0].max_band, 3.0);
    // Never moved: the moving threshold is band + standing.
    EXPECT_DOUBLE_EQ(c[0].thresholds.moving, 3.5);
    EXPECT_FALSE(c[0].note.empty());
}

TEST(MonitorEvents, StartEndPeakAndMedianOfAPulse) {
    std::vector<double> v(1000, 0.1);
    for (std::size_t i = 200; i < 400; ++i) v[i] = 5.0;
    v[250] = 7.0;  // the peak
    for (std::size_t i = 400; i < 420; ++i) v[i] = 0.5;  // under the threshold for 20 ms < hold: same event
    for (std::size_t i = 420; i < 450; ++i) v[i] = -4.0;
    const auto events = contact_events(replay_of(v), {{1.0, 0.0}}, 0.05);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_DOUBLE_EQ(events[0].start, 0.200);
    EXPECT_DOUBLE_EQ(events[0].end, 0.449);
    EXPECT_EQ(events[0].joints, std::vector<int>{0});
    EXPECT_DOUBLE_EQ(events[0].peak[0], 7.0);
    EXPECT_DOUBLE_EQ(events[0].peak_time[0], 0.250);
    EXPECT_DOUBLE_EQ(events[0].median[0], 5.0);
    // A hold shorter than the 20 ms dip: two events.
    EXPECT_EQ(contact_events(replay_of(v), {{1.0, 0.0}}, 0.01).size(), 2u);
}

TEST(MonitorEvents, ConfirmationDropsGlitchesAndDelaysTheStart) {
    std::vector<double> v(1000, 0.0);
    v[100] = 9.0;                                        // one sample
    for (std::size_t i = 500; i < 600; ++i) v[i] = 9.0;  // a contact
    EXPECT_EQ(contact_events(replay_of(v), {{1.0, 0.0}}, 0.05, 1).size(), 2u);
    const auto confirmed = contact_events(replay_of(v), {{1.0, 0.0}}, 0.05, 3);
    ASSERT_EQ(confirmed.size(), 1u);
    EXPECT_DOUBLE_EQ(confirmed[0].start, 0.502);
}

TEST(MonitorFile, RoundTripsAndRefusesWhatItCannotUse) {
    MonitorFile f;
    f.robot = "identified.yaml";
    f.estimator.estimator = Estimator::Residual;
    f.estimator.gain = 50.0;
    f.estimator.xi = 0.5;
    f.standing_velocity = {0.01, 0.02};
    f.confirm = 2;
    f.band_margin = {0.2, 0.4};
    f.thresholds = {{1.5, 0.25}, {3.0, 0.0}};
    f.calibrated_from = {"a.csv", "b.csv"};
    const MonitorFile g = parse_monitor_file(to_yaml(f), "m.yaml", 2);
    EXPECT_EQ(g.estimator.estimator, Estimator::Residual);
    EXPECT_DOUBLE_EQ(g.estimator.gain, 50.0);
    EXPECT_DOUBLE_EQ(g.estimator.xi, 0.5);
    EXPECT_EQ(g.standing_velocity, f.standing_velocity);
    EXPECT_EQ(g.confirm, 2);
    EXPECT_EQ(g.band_margin, f.band_margin);  // one per joint
    EXPECT_EQ(parse_monitor_file("joints: [{moving: 1, standing: 0}, {moving: 1, standing: 0}]\n", "m.yaml", 2).band_margin, std::vector<double>{0.0});  // optional
    EXPECT_EQ(parse_monitor_file("band_margin: 0.2\njoints: [{moving: 1, standing: 0}, {moving: 1, standing: 0}]\n", "m.yaml", 2).band_margin,
              std::vector<double>{0.2});  // one for all
    ASSERT_EQ(g.thresholds.size(), 2u);
    EXPECT_DOUBLE_EQ(g.thresholds[0].moving, 1.5);
    EXPECT_DOUBLE_EQ(g.thresholds[0].standing, 0.25);
    EXPECT_EQ(g.calibrated_from, f.calibrated_from);
    auto error_of = [](const std::string& yaml) {
        try {
            parse_monitor_file(yaml, "m.yaml", 2);
        } catch (const jacobid::InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(error_of("joints: [{moving: 1, standing: 0}]\n"), "m.yaml:1:9: joints: must be a list of 2 maps {moving: N.m, standing: N.m}, one per joint of the robot");
    EXPECT_NE(error_of("joints: [{moving: 1, standing: 0}, {moving: 1}]\n").find("joints[1].standing: missing"), std::string::npos);
    EXPECT_NE(error_of("estimator: {type: kalman}\njoints: [{moving: 1, standing: 0}, {moving: 1, standing: 0}]\n").find("estimator.type: expected observer or residual"), std::string::npos);
    EXPECT_NE(error_of("band_margin: -0.1\njoints: [{moving: 1, standing: 0}, {moving: 1, standing: 0}]\n").find("band_margin: must be >= 0"), std::string::npos);
    EXPECT_NE(error_of("band_margin: [0.1, 0.2, 0.3]\njoints: [{moving: 1, standing: 0}, {moving: 1, standing: 0}]\n").find("band_margin: must be one number or a list of 2"),
              std::string::npos);
    EXPECT_NE(error_of("gain: 3\njoints: [{moving: 1, standing: 0}, {moving: 1, standing: 0}]\n").find("gain"), std::string::npos);
}

}  // namespace
