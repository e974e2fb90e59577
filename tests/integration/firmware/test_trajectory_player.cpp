// SPDX-License-Identifier: MIT
// TrajectoryPlayer (firmware/, issue 17): the ramp from the measured pose (a quintic: its closed-form
// peak velocity 15/8 d / T and rest at both ends), every table row played in order and repeated, and each
// safety check stopping playback in the very cycle its input arrives. A simulated ideal drive (the measured
// position is the previous command) closes the loop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "allocation_counter.hpp"
#include "jacobid/firmware/trajectory_player.hpp"

namespace {

using jacobid::firmware::PlaybackConfig;
using jacobid::firmware::PlaybackPhase;
using jacobid::firmware::PlayerInput;
using jacobid::firmware::StopReason;
using jacobid::firmware::TrajectoryPlayer;
using jacobid::firmware::TrajectoryRow;

constexpr double kTs = 1e-3;
constexpr double kPi = 3.14159265358979323846;

// Two joints, one period of a cosine (closed: the last row is the first; at rest there, as the ramp-in
// leaves the robot), 500 rows; peak velocity 3.8 rad/s, peak acceleration 47 rad/s^2.
PlaybackConfig sine_config(int repeat = 1) {
    PlaybackConfig c;
    const int n = 500;
    for (int k = 0; k <= n; ++k) {
        TrajectoryRow r;
        const double w = 2.0 * kPi / (n * kTs);
        r.q[0] = 0.3 * (1.0 - std::cos(w * k * kTs));
        r.qd[0] = 0.3 * w * std::sin(w * k * kTs);
        r.q[1] = 1.0 - 0.2 * std::cos(w * k * kTs);
        r.qd[1] = 0.2 * w * std::sin(w * k * kTs);
        r.tau[1] = 2.0;
        c.rows.push_back(r);
    }
    for (int j = 0; j < 2; ++j) {
        c.position_min[j] = -2.0;
        c.position_max[j] = 2.0;
        c.velocity_limit[j] = 5.0;
        c.acceleration_limit[j] = 60.0;
        c.torque_limit[j] = 10.0;
        c.following_error[j] = 0.05;
        c.kp[j] = 50.0;
        c.kd[j] = 1.0;
    }
    c.ramp_time = 0.5;
    c.repeat = repeat;
    return c;
}

PlayerInput fresh_input(const TrajectoryPlayer& p, bool first, double q0 = 0.0, double q1 = 0.8) {
    PlayerInput in;
    in.fresh = {true, true};
    in.q[0] = first ? q0 : p.commands()[0].position;
    in.q[1] = first ? q1 : p.commands()[1].position;
    return in;
}

TEST(TrajectoryPlayer, RampStartsAtTheMeasuredPoseAndReachesTheFirstRowAtRest) {
    TrajectoryPlayer p;
    const PlaybackConfig c = sine_config();
    ASSERT_EQ(p.configure(c, 2, kTs), "");
    p.start();
    double peak = 0.0;
    const int ramp_cycles = 500;  // 0.5 s
    for (int k = 1; k <= ramp_cycles; ++k) {
        p.step(fresh_input(p, k == 1, 0.1, 0.8));
        ASSERT_EQ(p.phase(), k < ramp_cycles ? PlaybackPhase::RampIn : PlaybackPhase::Playing) << k;
        if (k == 1) {
            EXPECT_NEAR(p.commands()[0].position, 0.1, 1e-8) << "the ramp starts where the robot stands";
            EXPECT_NEAR(p.commands()[0].velocity, 0.0, 1e-4);
        }
        peak = std::max(peak, std::abs(p.commands()[1].velocity));
    }
    // Joint 2 stands at its first row already (1 - 0.2 = 0.8): its ramp does not move.
    EXPECT_NEAR(peak, 0.0, 1e-12);
    EXPECT_EQ(p.commands()[0].position, c.rows[0].q[0]) << "the last ramp cycle commands row 0 exactly";
    EXPECT_NEAR(p.commands()[0].velocity, 0.0, 1e-12);
    EXPECT_EQ(p.commands()[0].kp, 50.0);
}

TEST(TrajectoryPlayer, RampPeakVelocityIsTheQuinticsAndATooFastRampIsRefusedBeforeMoving) {
    TrajectoryPlayer p;
    PlaybackConfig c = sine_config();
    ASSERT_EQ(p.configure(c, 2, kTs), "");
    p.start();
    double peak = 0.0;
    for (int k = 1; k <= 500; ++k) {
        p.step(fresh_input(p, k == 1, -0.4, 0.8));
        peak = std::max(peak, std::abs(p.commands()[0].velocity));
    }
    EXPECT_NEAR(peak, 15.0 / 8.0 * 0.4 / 0.5, 1e-5);
    // A ramp from further away, whose peak (1.875 x 1.5 rad / 0.5 s = 5.6 rad/s) is above the velocity
    // limit 5 rad/s: stopped in the first cycle, naming joint 1.
    ASSERT_EQ(p.configure(c, 2, kTs), "");
    p.start();
    p.step(fresh_input(p, true, -1.5, 0.8));
    EXPECT_EQ(p.phase(), PlaybackPhase::Stopped);
    EXPECT_EQ(p.stop_reason(), StopReason::VelocityLimit);
    EXPECT_EQ(p.stop_joint(), 0);
    EXPECT_TRUE(p.stop_drives());
}

TEST(TrajectoryPlayer, PlaysEveryRowInOrderRepeatsWithoutTheDuplicateRowAndFinishes) {
    TrajectoryPlayer p;
    const PlaybackConfig c = sine_config(2);
    ASSERT_EQ(p.configure(c, 2, kTs), "");
    p.start();
    int k = 0;
    while (p.phase() == PlaybackPhase::RampIn) p.step(fresh_input(p, ++k == 1, 0.0, 0.8));
    const std::size_t n = c.rows.size();  // 501 rows, the last equal to the first
    std::size_t played = 0;
    std::size_t expected_row = 0;
    while (p.active()) {
        p.step(fresh_input(p, false));
        if (!p.active()) break;
        expected_row = expected_row + 1 < n ? expected_row + 1 : 1;
        ASSERT_EQ(p.row(), expected_row) << "command " << played;
        EXPECT_EQ(p.commands()[0].position, c.rows[expected_row].q[0]);
        EXPECT_EQ(p.commands()[1].velocity, c.rows[expected_row].qd[1]);
        EXPECT_EQ(p.commands()[1].torque, 2.0);
        ++played;
    }
    EXPECT_EQ(p.phase(), PlaybackPhase::Finished);
    EXPECT_EQ(played, 2 * (n - 1)) << "two passes of 500 steps";
}

// Plays 100 cycles, then injects `fault` into one cycle's input: playback must stop in that cycle.
void expect_stop_in_the_same_cycle(void (*fault)(PlayerInput&), StopReason reason, int joint, std::uint32_t max_stale = 0) {
    TrajectoryPlayer p;
    PlaybackConfig c = sine_config();
    c.max_stale_cycles = max_stale;
    ASSERT_EQ(p.configure(c, 2, kTs), "");
    p.start();
    for (int k = 1; k <= 100; ++k) p.step(fresh_input(p, k == 1));
    ASSERT_TRUE(p.active());
    const std::uint64_t before = p.cycles();
    for (std::uint32_t extra = 0; extra <= max_stale; ++extra) {
        PlayerInput in = fresh_input(p, false);
        fault(in);
        p.step(in);
        if (extra < max_stale) {
            ASSERT_TRUE(p.active()) << "stale for " << extra + 1 << " cycle(s) is allowed";
        }
    }
    EXPECT_EQ(p.phase(), PlaybackPhase::Stopped);
    EXPECT_EQ(p.stop_reason(), reason) << jacobid::firmware::to_string(p.stop_reason());
    EXPECT_EQ(p.stop_joint(), joint);
    EXPECT_EQ(p.cycles(), before + max_stale) << "no command after the faulty input";
    p.step(fresh_input(p, false));
    EXPECT_TRUE(p.stop_drives()) << "latched";
}

TEST(TrajectoryPlayer, EachFaultStopsPlaybackInTheCycleItArrives) {
    expect_stop_in_the_same_cycle([](PlayerInput& in) { in.estop = true; }, StopReason::EStop, -1);
    expect_stop_in_the_same_cycle([](PlayerInput& in) { in.deadline_missed = true; }, StopReason::MissedDeadline, -1);
    expect_stop_in_the_same_cycle([](PlayerInput& in) { in.fault[1] = true; }, StopReason::DriveFault, 1);
    expect_stop_in_the_same_cycle([](PlayerInput& in) { in.fresh[0] = false; }, StopReason::StaleJoint, 0);
    expect_stop_in_the_same_cycle([](PlayerInput& in) { in.fresh[1] = false; }, StopReason::StaleJoint, 1, 3);
    expect_stop_in_the_same_cycle([](PlayerInput& in) { in.q[1] += 0.06; }, StopReason::FollowingError, 1);
}

TEST(TrajectoryPlayer, StartOutsideThePositionLimitsIsRefusedBeforeMoving) {
    TrajectoryPlayer p;
    ASSERT_EQ(p.configure(sine_config(), 2, kTs), "");
    p.start();
    p.step(fresh_input(p, true, 0.0, 2.01));  // joint 2 stands beyond its upper limit
    EXPECT_EQ(p.stop_reason(), StopReason::PositionLimit);
    EXPECT_EQ(p.stop_joint(), 1);
}

TEST(TrajectoryPlayer, ConfigureNamesTheRowAndJointBeyondALimit) {
    TrajectoryPlayer p;
    PlaybackConfig c = sine_config();
    c.rows[42].tau[1] = 11.0;
    EXPECT_EQ(p.configure(c, 2, kTs), "trajectory table row 43: joint 2: torque 11 N.m beyond the limit 10 N.m (trajectory.joints[1].torque)");
    c = sine_config();
    c.following_error[0] = 0.0;
    EXPECT_EQ(p.configure(c, 2, kTs), "trajectory: joint 1: following_error > 0 is required");
    c = sine_config();
    c.rows[7].q[0] = std::nan("");
    EXPECT_EQ(p.configure(c, 2, kTs), "trajectory table row 8: joint 1: not a finite number");
    EXPECT_NE(p.configure(sine_config(), 9, kTs), "");
}

TEST(TrajectoryPlayer, StepAllocatesNothing) {
    TrajectoryPlayer p;
    ASSERT_EQ(p.configure(sine_config(100), 2, kTs), "");
    p.start();
    p.step(fresh_input(p, true));
    const auto before = jacobid::test::allocation_count();
    for (int k = 0; k < 20000 && p.active(); ++k) p.step(fresh_input(p, false));
    EXPECT_EQ(jacobid::test::allocation_count(), before);
    EXPECT_TRUE(p.active()) << "still playing after 20000 cycles (100 passes)";
}

}  // namespace
