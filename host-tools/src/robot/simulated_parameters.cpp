// SPDX-License-Identifier: MIT
#include "robot/simulated_parameters.hpp"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.hpp"

namespace jacobid::robot {
namespace {

// Far beyond any robot (kg, kg.m^2, N.m.s/rad, m, rad) and far below where the dynamics' products overflow.
constexpr double kMaxParameter = 1e9;
constexpr double kMaxJointLimit = 1e4;   // rad or m: ~1600 turns
constexpr double kMaxGravity = 1e3;      // m/s^2
// Smallest / largest eigenvalue of the mass matrix below which it is singular for the integrator.
constexpr double kMinInertiaRatio = 1e-10;
constexpr int kSampledConfigurations = 64;

// Kinds that no body has negative: masses, diagonal inertias, rotor inertias, viscous and Coulomb friction.
// Regrouped base parameters (a trailing 'R', e.g. XX2R = XX2 - YY2) may be negative and are left to the
// mass matrix check.
bool must_be_nonnegative(const std::string& name) {
    const std::size_t digits = name.find_first_of("0123456789");
    if (digits == std::string::npos || name.back() == 'R') return false;
    const std::string kind = name.substr(0, digits);
    return kind == "M" || kind == "XX" || kind == "YY" || kind == "ZZ" || kind == "IA" || kind == "FV" || kind == "FC";
}

void check_value(const RobotDescription& d, const std::string& name, double value) {
    if (!std::isfinite(value) || std::abs(value) > kMaxParameter) {
        throw InputError(fmt::format("{}: parameter {} = {}: expected a finite value within +-{:g} (SI units)", d.source, name, value, kMaxParameter));
    }
    if (must_be_nonnegative(name) && value < 0.0) {
        throw InputError(fmt::format("{}: parameter {} = {}: a mass, inertia or friction coefficient must be >= 0 (no robot can be simulated with it)",
                                     d.source, name, value));
    }
}

void check_limits(const RobotDescription& d) {
    for (std::size_t j = 0; j < d.joints.size(); ++j) {
        const JointDescription& joint = d.joints[j];
        for (double limit : {joint.lower_limit, joint.upper_limit}) {
            if (!std::isfinite(limit) || std::abs(limit) > kMaxJointLimit) {
                throw InputError(fmt::format("{}: joint {} ({}) limit {}: expected finite limits within +-{:g} (rad or m) for the simulated moves",
                                             d.source, j + 1, joint.name, limit, kMaxJointLimit));
            }
        }
    }
    if (!d.gravity.allFinite() || d.gravity.norm() > kMaxGravity) {
        throw InputError(fmt::format("{}: gravity [{}]: expected a finite vector of at most {:g} m/s^2", d.source, fmt::join(d.gravity, ", "), kMaxGravity));
    }
}

// A configuration in the joint range: the start (the range's middle or 0) and then a low-discrepancy cover.
Eigen::VectorXd sampled_configuration(const RobotDescription& d, int k) {
    Eigen::VectorXd q(static_cast<Eigen::Index>(d.joints.size()));
    static const double kPrimes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53};
    for (std::size_t j = 0; j < d.joints.size(); ++j) {
        const double lower = d.joints[j].lower_limit, upper = d.joints[j].upper_limit;
        double u = 0.5;
        if (k > 0) {  // Halton sequence, one prime base per joint
            u = 0.0;
            double f = 1.0;
            for (int i = k; i > 0; i /= static_cast<int>(kPrimes[j % 16])) {
                f /= kPrimes[j % 16];
                u += f * (i % static_cast<int>(kPrimes[j % 16]));
            }
        }
        q[static_cast<Eigen::Index>(j)] = lower + u * (upper - lower);
    }
    return q;
}

void check_mass_matrix(const RobotDescription& d, const RobotModel& model, const Eigen::VectorXd& x) {
    if (static_cast<int>(d.joints.size()) != model.joint_count()) return;
    ForwardDynamics dynamics(model, x);
    for (int k = 0; k < kSampledConfigurations; ++k) {
        const Eigen::VectorXd q = sampled_configuration(d, k);
        const Eigen::MatrixXd M = dynamics.inertia(q.data());
        const std::string at = fmt::format("at q = [{:.4g}]", fmt::join(q, ", "));
        if (!M.allFinite()) throw InputError(fmt::format("{}: the mass matrix {} is not finite (parameters too large)", d.source, at));
        const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M, Eigen::EigenvaluesOnly).eigenvalues();
        if (eig.maxCoeff() <= 0.0) {
            throw InputError(fmt::format("{}: the robot has no inertia {} (no masses, inertias or rotor inertias: a URDF without <inertial>?); "
                                         "it cannot be simulated",
                                         d.source, at));
        }
        if (eig.minCoeff() <= kMinInertiaRatio * eig.maxCoeff()) {
            Eigen::Index worst = 0;
            M.diagonal().minCoeff(&worst);
            throw InputError(fmt::format("{}: the mass matrix {} is not positive definite (eigenvalues {:.3g} .. {:.3g}; smallest diagonal: joint "
                                         "{}): a negative or zero mass or inertia, which no robot can have",
                                         d.source, at, eig.minCoeff(), eig.maxCoeff(), worst + 1));
        }
    }
}

}  // namespace

Eigen::VectorXd simulated_parameters(const RobotDescription& description, const RobotModel& model) {
    check_limits(description);
    for (const auto* list : {&description.model_parameters, &description.parameters}) {
        for (const auto& [name, value] : *list) check_value(description, name, value);
    }
    const Eigen::VectorXd x = true_parameters(description, model);
    for (int c = 0; c < model.parameter_count(); ++c) check_value(description, model.parameter_names()[static_cast<std::size_t>(c)], x[c]);
    check_mass_matrix(description, model, x);
    return x;
}

}  // namespace jacobid::robot
