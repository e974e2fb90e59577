// SPDX-License-Identifier: MIT
#pragma once
// Successive point-to-point moves with quintic (5th-order polynomial) time laws, the reference of the
// paper's PD-controlled robot: every move starts and ends at rest (zero velocity and acceleration), all
// joints move together over the same duration, targets are drawn uniformly within the joint limits. With
// velocity or acceleration limits, a move lasts at least as long as its largest step needs to stay within
// them: a quintic step d over T peaks at 15/8 d / T in velocity and 10 / sqrt(3) d / T^2 in acceleration.
// Seeded, so a log can be regenerated exactly.
#include <cstdint>
#include <random>
#include <vector>

namespace jacobid::sim {

// A quintic step d over T peaks at kQuinticPeakVelocity d / T and kQuinticPeakAcceleration d / T^2.
inline constexpr double kQuinticPeakVelocity = 1.875;                  // 15/8
inline constexpr double kQuinticPeakAcceleration = 5.773502691896258;  // 10 / sqrt(3)

struct MoveSettings {
    double min_duration = 0.6;  // s; fast moves as in docs/method.md, "Pitfalls" (0.6-1.6 s)
    double max_duration = 1.6;  // s
    double max_dwell = 0.2;     // s of rest after each move, uniform in [0, max_dwell]
    // rad/s and rad/s^2 of the reference: empty (none), one for every joint, or one per joint (> 0).
    std::vector<double> velocity_limit, acceleration_limit;
};

struct ReferenceSample {
    std::vector<double> q, qd, qdd;
};

class QuinticTrajectory {
public:
    // Starts at rest at `start`; targets uniform in [lower[j], upper[j]]. InputError when a limit list has
    // neither one value nor one per joint.
    QuinticTrajectory(std::vector<double> start, std::vector<double> lower, std::vector<double> upper, MoveSettings settings,
                      std::uint64_t seed);
    // Reference at time t; t must not decrease between calls (moves are drawn on the fly).
    void evaluate(double t, ReferenceSample& out);

private:
    void next_move();

    std::vector<double> lower_, upper_;
    MoveSettings settings_;
    std::vector<double> velocity_limit_, acceleration_limit_;  // per joint (infinity: none)
    std::mt19937_64 rng_;
    std::vector<double> from_, to_;
    double move_start_ = 0.0;
    double move_duration_ = 1.0;
    double move_end_ = 0.0;  // end of move + dwell
};

}  // namespace jacobid::sim
