// SPDX-License-Identifier: MIT
#pragma once
// Short-horizon simulation of an identified model against the measured positions: segments of a few
// tenths of a second, each started from the measured state (position from the log, velocity from the Jacobi
// estimate) and driven by the measured torque (linear between samples, read `delay` later when a torque
// delay was identified), integrated with RK4 at the log's sample period through robot::ForwardDynamics, as
// the simulator integrates the truth. Over a short horizon a model error shows as a position drift before
// the open-loop integration of noise dominates; over long horizons an open-loop PD-controlled robot drifts
// whatever the model.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "identify/pipeline/pipeline.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::diagnose {

struct HorizonSettings {
    double horizon = 0.3;   // s
    double spacing = 0.5;   // s between segment starts
    double diverged_at = 1.0;  // rad: a simulated position this far from the measured one has diverged
};

// A segment whose open-loop simulation left the measured path by more than HorizonSettings::diverged_at
// (or produced no finite state, or met an inertia matrix that is not positive definite). Such a segment says
// that the identified model cannot be integrated there, not how large its error is: it is reported and
// excluded from the RMS figures.
struct DivergedSegment {
    double t = 0.0;      // s, start of the segment
    double after = 0.0;  // s into the segment
    int joint = -1;      // 0-based joint that left the path (-1: every joint, e.g. inertia not positive definite)
    std::string why;
};

struct HorizonResult {
    std::size_t segments = 0;        // simulated, diverged ones included
    std::vector<double> rms_error;   // per joint, rad, over every sample of the segments that did not diverge (NaN: none)
    std::vector<double> end_error;   // per joint, rad, RMS of the error at the end of those segments (NaN: none)
    std::size_t diverged = 0;
    std::vector<DivergedSegment> divergences;  // the first few (kMaxListed)
    static constexpr std::size_t kMaxListed = 5;
    // "k of N segments diverged (first at t = .. s, joint j after .. s: why); excluded", or "" when none did.
    std::string divergence_summary() const;
};

// x: the model's parameters (NaN counts as 0).
HorizonResult simulate_horizons(const robot::RobotModel& model, const Eigen::VectorXd& x, const identify::LogColumns& log,
                                const identify::StateEstimates& states, double delay, const HorizonSettings& settings);

// Several logs' results as one (diagnose --in a.csv --in b.csv): segments and divergences added (the first
// kMaxListed kept, in order), each figure pooled over the segments kept in every log (a segment compares the
// same number of samples in each, the horizon being the same).
HorizonResult pooled_horizons(const std::vector<HorizonResult>& parts);

}  // namespace jacobid::diagnose
