// SPDX-License-Identifier: MIT
// The start-up check of the steps a trajectory table commands (issue 36, fwconfig/src/trajectory_motion.cpp):
// a jump between rows whose own values are within the limits, a velocity column that does not describe the
// positions, positions that accelerate beyond the limit, a table that does not start at rest after the
// ramp-in, and a table that does not join its start at the wrap (repeat > 1) are refused by configure(),
// naming the row, the joint, the step and the limit; smooth, periodic and unclosed-but-single-pass tables
// are accepted.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "jacobid/fwconfig/trajectory_motion.hpp"
#include "jacobid/firmware/trajectory_player.hpp"

namespace {

using namespace jacobid::firmware;

constexpr double kTs = 1e-3;
constexpr double kPi = 3.14159265358979323846;

// One joint at 1 kHz, limits +-3 rad, 5 rad/s, 60 rad/s^2; `rows` rows of q = f(k), qd = g(k).
template <typename Q, typename Qd>
PlaybackConfig table(int rows, Q q, Qd qd, int repeat = 1) {
    PlaybackConfig c;
    for (int k = 0; k < rows; ++k) {
        TrajectoryRow r;
        r.q[0] = q(k);
        r.qd[0] = qd(k);
        c.rows.push_back(r);
    }
    c.position_min[0] = -3.0;
    c.position_max[0] = 3.0;
    c.velocity_limit[0] = 5.0;
    c.acceleration_limit[0] = 60.0;
    c.torque_limit[0] = 10.0;
    c.following_error[0] = 0.05;
    c.ramp_time = 0.5;
    c.repeat = repeat;
    return c;
}

// q = A (1 - cos(w t)) over `rows` rows: at rest at t = 0; a whole period when rows = period + 1.
PlaybackConfig cosine(int rows, int period, double amplitude = 0.3, int repeat = 1) {
    const double w = 2.0 * kPi / (period * kTs);
    return table(
        rows, [=](int k) { return amplitude * (1.0 - std::cos(w * k * kTs)); }, [=](int k) { return amplitude * w * std::sin(w * k * kTs); }, repeat);
}

std::string configure(const PlaybackConfig& c) {
    TrajectoryPlayer p;
    return p.configure(c, 1, kTs);
}

TEST(TrajectoryMotion, SmoothPeriodicTablesAreAccepted) {
    EXPECT_EQ(configure(cosine(501, 500, 0.3, 3)), "") << "closed: the last row is the first, the next pass starts at the second";
    EXPECT_EQ(configure(cosine(500, 500, 0.3, 3)), "") << "one period without the closing row: the wrap to row 0 is one more step";
    EXPECT_EQ(configure(cosine(251, 500, 0.3, 1)), "") << "half a period, played once: no wrap";
}

// The example: a 2 rad jump between two rows, the velocity column (zero) and every row within the limits.
TEST(TrajectoryMotion, AJumpBetweenRowsIsRefusedNamingTheRowJointStepAndLimit) {
    const PlaybackConfig c = table(10, [](int k) { return k < 5 ? 0.0 : 2.0; }, [](int) { return 0.0; });
    EXPECT_EQ(configure(c), "trajectory table row 6: joint 1: the position steps 2 rad from row 5, 2000 rad/s at 1000 Hz, beyond the velocity "
                            "limit 5 rad/s (trajectory.joints[0].velocity, +1 %)");
    // A step just within the limit (4.9 rad/s) passes that check, 5.1 rad/s does not.
    EXPECT_EQ(configure(table(3, [](int k) { return k == 2 ? 0.0049 : 0.0; }, [](int) { return 0.0; })).find("velocity limit"), std::string::npos);
    EXPECT_NE(configure(table(3, [](int k) { return k == 2 ? 0.0051 : 0.0; }, [](int) { return 0.0; })).find("row 3: joint 1: the position steps 0.0051 rad"),
              std::string::npos);
}

TEST(TrajectoryMotion, AVelocityColumnThatIsNotTheDerivativeOfThePositionsIsRefused) {
    // The velocity column left at zero while the positions move (3.8 rad/s at most).
    PlaybackConfig zero = cosine(501, 500);
    for (auto& r : zero.rows) r.qd[0] = 0.0;
    const std::string why = configure(zero);
    EXPECT_EQ(why.rfind("trajectory table row ", 0), 0u) << why;
    EXPECT_NE(why.find("joint 1: the position step from row "), std::string::npos) << why;
    EXPECT_NE(why.find("but the velocity column says 0 and 0 rad/s"), std::string::npos) << why;
    EXPECT_NE(why.find("q1 and qd1 do not describe one motion"), std::string::npos) << why;
    // The velocity column of the opposite sign (another convention, or another joint's).
    PlaybackConfig flipped = cosine(501, 500);
    for (auto& r : flipped.rows) r.qd[0] = -r.qd[0];
    EXPECT_NE(configure(flipped).find("do not describe one motion"), std::string::npos) << configure(flipped);
}

TEST(TrajectoryMotion, AccelerationBeyondTheLimitIsRefusedFromTheVelocityColumnAndFromThePositions) {
    // Velocity 0 then 1 rad/s from row 6 on, positions consistent: a velocity step of 1 rad/s in 1 ms.
    const PlaybackConfig kink = table(10, [](int k) { return k < 5 ? 0.0 : (k - 5) * 1e-3; }, [](int k) { return k < 5 ? 0.0 : 1.0; });
    EXPECT_EQ(configure(kink), "trajectory table row 6: joint 1: the velocity column steps 1 rad/s from row 5, 1000 rad/s^2 at 1000 Hz, beyond the "
                               "acceleration limit 60 rad/s^2 (trajectory.joints[0].acceleration, +1 %)");
    // Positions zigzagging by 7e-5 rad (0.07 rad/s, within the velocity column's slack around 0): the
    // commanded positions accelerate at 140 rad/s^2 although the velocity column is flat.
    const PlaybackConfig zigzag = table(10, [](int k) { return k % 2 == 1 ? 7e-5 : 0.0; }, [](int) { return 0.0; });
    EXPECT_NE(configure(zigzag).find("trajectory table row 3: joint 1: the positions of row 1 at rest (the end of the ramp-in), row 2 and row 3 "
                                     "accelerate at -140 rad/s^2 at 1000 Hz, beyond the acceleration limit 60 rad/s^2"),
              std::string::npos)
        << configure(zigzag);
}

// The ramp-in ends at rest on row 0; a table that starts moving there would get its whole first velocity
// in one cycle. In torque mode there is no ramp and no such step.
TEST(TrajectoryMotion, ATableThatDoesNotStartAtRestIsRefusedAfterTheRampIn) {
    const double w = 2.0 * kPi / 0.5;
    PlaybackConfig moving = table(501, [=](int k) { return 0.3 * std::sin(w * k * kTs); }, [=](int k) { return 0.3 * w * std::cos(w * k * kTs); });
    const std::string why = configure(moving);
    EXPECT_EQ(why.rfind("trajectory table row 2: joint 1: the velocity column steps 3.77", 0), 0u) << why;
    EXPECT_NE(why.find("from row 1 at rest (the end of the ramp-in)"), std::string::npos) << why;
    EXPECT_NE(why.find("the ramp-in ends at rest on the first row, so the table must start at rest"), std::string::npos) << why;
    moving.mode = jacobid::hal::CommandMode::Torque;
    EXPECT_EQ(configure(moving), "");
}

// The second example: a table that does not end where it starts, played 3 times, wrapped to row 0
// in one cycle (here a 0.4 rad step). Refused naming the wrap; the same table played once is accepted.
TEST(TrajectoryMotion, AWrapThatDoesNotJoinTheStartIsRefused) {
    const PlaybackConfig half = cosine(251, 500, 0.2, 3);  // 0 -> 0.4 rad, at rest at both ends
    const std::string why = configure(half);
    EXPECT_EQ(why.rfind("trajectory table row 1: joint 1: the position steps -0.4 rad from row 251, -400 rad/s at 1000 Hz, beyond the velocity "
                        "limit 5 rad/s (trajectory.joints[0].velocity, +1 %); this is the wrap from the table's last row (row 251) to its next "
                        "pass (repeat: 3)",
                        0),
              0u)
        << why;
    EXPECT_NE(why.find("or set repeat: 1"), std::string::npos) << why;
    PlaybackConfig once = half;
    once.repeat = 1;
    EXPECT_EQ(configure(once), "");
    // Closed in position but not in velocity: q = A s^2 (1 - s), s = t / 0.5 s, starts at rest and ends on
    // its first pose moving at -A / 0.5 s = -1 rad/s; the next pass starts at rest.
    const PlaybackConfig returning = table(
        501, [](int k) { const double s = k / 500.0; return 0.5 * s * s * (1.0 - s); },
        [](int k) { const double s = k / 500.0; return 0.5 * (2.0 * s - 3.0 * s * s) / 0.5; }, 2);
    const std::string kinked = configure(returning);
    EXPECT_EQ(kinked.rfind("trajectory table row 2: joint 1: the velocity column steps 1.004 rad/s from row 501", 0), 0u) << kinked;
    EXPECT_NE(kinked.find("this is the wrap"), std::string::npos) << kinked;
}

// A refused table leaves the player unconfigured: start() and step() command nothing.
TEST(TrajectoryMotion, ARefusedTableIsNeverPlayed) {
    TrajectoryPlayer p;
    ASSERT_EQ(p.configure(cosine(501, 500), 1, kTs), "");
    ASSERT_NE(p.configure(table(10, [](int k) { return k < 5 ? 0.0 : 2.0; }, [](int) { return 0.0; }), 1, kTs), "");
    p.start();
    PlayerInput in;
    in.fresh[0] = true;
    p.step(in);
    EXPECT_EQ(p.phase(), PlaybackPhase::Idle);
    EXPECT_FALSE(p.active());
    EXPECT_EQ(p.cycles(), 0u);
}

// The ramp-in from where the robot stands: its quintic's peak acceleration 10/sqrt(3) d / T^2 (here
// 0.1 rad in 0.05 s: 231 rad/s^2, while its peak velocity 3.75 rad/s is within the limit) stops the
// playback in its first cycle, before anything moves.
TEST(TrajectoryMotion, ARampInBeyondTheAccelerationLimitStopsBeforeMoving) {
    TrajectoryPlayer p;
    PlaybackConfig c = cosine(501, 500);
    c.ramp_time = 0.05;
    ASSERT_EQ(p.configure(c, 1, kTs), "");
    p.start();
    PlayerInput in;
    in.fresh[0] = true;
    in.q[0] = -0.1;
    p.step(in);
    EXPECT_EQ(p.phase(), PlaybackPhase::Stopped);
    EXPECT_EQ(p.stop_reason(), StopReason::AccelerationLimit);
    EXPECT_EQ(p.stop_joint(), 0);
    EXPECT_STREQ(to_string(p.stop_reason()), "acceleration limit");
    // From 0.02 rad (46 rad/s^2) it ramps.
    ASSERT_EQ(p.configure(c, 1, kTs), "");
    p.start();
    in.q[0] = -0.02;
    p.step(in);
    EXPECT_EQ(p.phase(), PlaybackPhase::RampIn);
}

}  // namespace
