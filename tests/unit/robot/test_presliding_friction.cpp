// SPDX-License-Identifier: MIT
// Dahl presliding state and play operator (lib/include/jacobid/robot/presliding_friction.hpp) against
// independent references: the analytic response to a ramp after a reversal, a fine explicit Euler
// integration of ds/dx = (1 - s sgn(dx)) / x_p, and the play operator's hand-computed output.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "jacobid/robot/presliding_friction.hpp"

namespace jr = jacobid::robot;

TEST(DahlState, RampAfterReversalFromSaturationFollowsTheAnalyticResponse) {
    const double xp = 3e-4;
    jr::DahlState s(xp, -1.0);  // saturated by a long motion in the negative direction
    double x = 0.0;
    for (int k = 1; k <= 400; ++k) {
        const double dx = 5e-6 * (1.0 + 0.5 * std::sin(k));  // a ramp at an uneven speed: only the path counts
        x += dx;
        const double got = s.step(dx);
        EXPECT_NEAR(got, 1.0 - 2.0 * std::exp(-x / xp), 1e-12) << "x = " << x;
    }
    EXPECT_GT(s.state(), 0.99);
}

TEST(DahlState, AgreesWithAFineEulerIntegrationOverReversals) {
    const double xp = 2e-4;
    jr::DahlState exact(xp, 0.3);
    double euler = 0.3;
    for (int k = 0; k < 2000; ++k) {
        const double dx = 4e-6 * std::sin(0.01 * k) + 1e-6 * std::cos(0.37 * k);
        exact.step(dx);
        const int sub = 1000;
        for (int i = 0; i < sub; ++i) {
            const double h = dx / sub;
            euler += (1.0 - euler * (h > 0 ? 1.0 : (h < 0 ? -1.0 : 0.0))) / xp * h;
        }
        ASSERT_NEAR(exact.state(), euler, 2e-4) << "step " << k;
        ASSERT_LE(std::abs(exact.state()), 1.0);
    }
}

TEST(DahlState, StandsStillWithoutDisplacementAndNeverLeavesTheUnitInterval) {
    jr::DahlState s(1e-4, 0.42);
    EXPECT_EQ(s.step(0.0), 0.42);
    EXPECT_LE(s.step(10.0), 1.0);
    EXPECT_NEAR(s.state(), 1.0, 1e-15);
    EXPECT_GE(s.step(-10.0), -1.0);
}

TEST(PlayOperator, RemovesOneStepFlickerAndFollowsLargerMotionWithALag) {
    const double r = 1e-4;
    jr::PlayOperator play(r);
    EXPECT_EQ(play.step(0.5), 0.5);
    for (int k = 0; k < 50; ++k) EXPECT_EQ(play.step(0.5 + (k % 2) * 1e-4), 0.5);  // one quantization step of flicker
    EXPECT_NEAR(play.step(0.5003), 0.5002, 1e-15);  // leaves the band: follows at distance r
    EXPECT_NEAR(play.step(0.5004), 0.5003, 1e-15);
    EXPECT_NEAR(play.step(0.5003), 0.5003, 1e-15);  // reversal inside the band: holds
    EXPECT_NEAR(play.step(0.5001), 0.5002, 1e-15);  // and follows the other way at distance r
}

TEST(PreslidingFriction, FlickerAtRestKeepsTheMemoryThatRawPositionsErase) {
    const double xp = 2e-4, quantum = 1e-4;
    jr::PreslidingFriction played(xp, quantum);  // play half-width one step (a band two steps wide)
    jr::PreslidingFriction raw(xp, 0.0);
    for (int k = 0; k <= 200; ++k) played.step(-0.02 * k / 200.0), raw.step(-0.02 * k / 200.0);  // move negatively: s -> -1
    EXPECT_LT(played.state(), -0.99);
    for (int k = 0; k < 500; ++k) {
        const double q = -0.02 + (k % 2) * quantum;  // at rest, flickering by one step
        played.step(q);
        raw.step(q);
    }
    EXPECT_LT(played.state(), -0.99);           // the held friction keeps the sign of the last motion
    EXPECT_GT(std::abs(raw.state() + 1.0), 0.3);  // raw flicker drives the state away from saturation
}
