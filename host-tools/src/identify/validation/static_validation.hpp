// SPDX-License-Identifier: MIT
#pragma once
// Validation on a log where the robot holds a pose (identify --validate with a static log): the classic
// gravity check. At rest the model predicts tau = D(q, 0, 0) X (gravity and any friction offset; the
// Coulomb term of a smoothed or sign model is 0 at qd = 0), and the measured torque is compared with it
// joint by joint. A joint at rest can hold any torque within its static friction band, so the error is
// also reported against the identified Coulomb level FCj: an error inside +-FCj is friction, one outside it
// is a model error (gravity parameters, drive gain, payload).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "identify/pipeline/pipeline.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::identify {

struct StaticJointError {
    double measured = 0.0;        // N.m, mean over the log
    double measured_std = 0.0;    // N.m, sample std of the measured torque (noise, not the mean's uncertainty)
    double predicted = 0.0;       // N.m
    double error = 0.0;           // N.m, measured - predicted
    double coulomb = 0.0;         // N.m, identified Coulomb level of the joint (NaN: the model has none)
    bool within_friction = false;  // |error| <= coulomb
};

struct StaticValidationResult {
    std::string source;
    std::size_t samples = 0;
    std::vector<double> pose;  // rad, mean position per joint
    std::vector<StaticJointError> joints;
    double relative_error = 0.0;  // ||measured - predicted|| / ||measured|| over the joints
};

// True when no joint moves more than `min_joint_motion` (rad) over the log.
bool is_static(const LogColumns& log, double min_joint_motion);

// Parameters not identified (NaN in x) count as 0.
StaticValidationResult validate_static(const robot::RobotModel& model, const LogColumns& log, const Eigen::VectorXd& x);

}  // namespace jacobid::identify
