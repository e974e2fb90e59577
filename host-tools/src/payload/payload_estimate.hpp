// SPDX-License-Identifier: MIT
#pragma once
// `jacobid payload`: the ten inertial parameters of a payload on the last link with the arm held at its
// identified values (docs/identify.md, "Payload"; docs/method.md, "Payload identification").
//
// Rows: identify's pipeline (Jacobi differentiation, F_p, decimation) on the loaded run, or on the difference of
// the loaded and unloaded runs of one trajectory after aligning them in time (time_alignment.hpp), folded by
// PayloadRows. Unknowns: the payload's standard parameters phi about the last link's frame; the least squares,
// rank test and std are identify's (solve_least_squares, with its weighting and joint-HAC std). A known mass
// (--mass) moves its column to the right-hand side. A parameter the rows do not determine (a null direction of
// the rank test) is fixed to the prior "point mass": zero inertia about the centre of mass (its inertia
// about the link origin m(|c|^2 E - c c^T)), or a zero first moment, and the others are solved again.
//
// Std: the least squares' own (noise), plus what the payload inherits (first-order, phi = H^-1 A^T S t):
//   - the arm's parameters theta (held; dphi/dtheta = -H^-1 A^T S W) with their identified std, independent
//     (identify writes no correlations); zero in difference mode, where the arm cancels;
//   - each joint's drive gain, a relative error delta_j scaling that joint's effort (dphi/ddelta_j =
//     H^-1 A^T S Y_j), with the std given (--gain-std). What is not included is said (PayloadEstimate::left_out).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "identify/identify_run.hpp"
#include "payload/arm_file.hpp"
#include "payload/payload_inertia.hpp"
#include "payload/time_alignment.hpp"

namespace jacobid::payload {

struct PayloadSettings {
    identify::IdentifySettings identify;
    std::optional<double> mass;                           // kg, known
    Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();  // the output frame in the last link's frame
    std::string frame_name;                               // how the output frame was named
    std::vector<double> gain_std;                         // per joint, relative (0.01 = 1 %); empty: left out
};

enum class Status { Identified, Known, Prior };
const char* to_string(Status s);

using Matrix10 = Eigen::Matrix<double, 10, 10>;

struct PayloadEstimate {
    Standard10 standard = Standard10::Zero();  // about the last link's frame origin, XX..M
    Status status[10] = {};
    Matrix10 cov_noise = Matrix10::Zero(), cov_arm = Matrix10::Zero(), cov_gain = Matrix10::Zero();
    Matrix10 covariance() const { return cov_noise + cov_arm + cov_gain; }
    // The payload in the output frame, and the std of flatten(inertial) per source (delta method).
    Inertial inertial;
    Inertial10 std_total, std_noise, std_arm, std_gain;
    // d(mass)/d(delta_j): the mass change per relative gain error of joint j (kg per 1.0).
    std::vector<double> mass_gain_sensitivity;
    identify::LsSolution solution;  // the last solve (free payload parameters; names XX..M, then the arm's and Y1..)
    std::vector<identify::Unidentifiable> unidentifiable;  // of the first solve: which combinations the rows miss
    identify::PipelineInfo info;
    identify::TorqueDelayResult delay;
    bool delay_from_arm = false;  // the delay the arm's identification applied (its JSON), not --torque-delay's
    std::optional<Alignment> alignment;
    std::string loaded_source, unloaded_source, arm_source;
    std::vector<std::string> included, left_out;  // the std's sources
    std::vector<std::string> violations;          // physical consistency (payload_inertia.hpp)
    // The free fit's inertia (link frame's axes) when it was not determined and the six inertias were fixed to the prior.
    std::optional<Inertial> inertia_free_fit;
    std::vector<std::string> warnings;
    std::string frame_name;
    Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
};

// InputError for logs of another joint count than the arm, a log too short, gain_std of another size, a mass
// that the rows cannot determine.
PayloadEstimate estimate_payload(const ArmModel& arm, const identify::LogColumns& loaded, const identify::LogColumns* unloaded,
                                 const PayloadSettings& settings);

}  // namespace jacobid::payload
