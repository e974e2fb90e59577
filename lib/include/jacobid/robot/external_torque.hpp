// SPDX-License-Identifier: MIT
#pragma once
// External-torque estimators of a serial robot (M qdd + C qd + g + f = tau + tau_ext, tau the motor torque) from its identified model (docs/method.md, "External torque
// and contact detection"). Both see the joints through the same samples (q, qd and, for the residual, qdd)
// and the motor torque tau; both subtract the identified friction of joint_friction.hpp and report, per
// joint, the Coulomb band that friction can hold at standstill.
//
//  - MomentumObserver: the generalized-momentum observer (De Luca et al.),
//        r = K (p - p0 - integral(tau + C^T qd - g - f + r) dt),   p = M(q) qd,
//    needs no acceleration; in continuous time dr/dt = K (tau_ext - r): r is tau_ext through a first-order
//    low-pass of time constant 1/K per joint. Discretised with the trapezoidal rule on the model terms and
//    the backward Euler rule on the r feedback, r_k (1 + K T) = K (p_k - p0 - I_k - T sum_{i<k} r_i), which is
//    stable for every K T (a 100 Hz log with K = 200/s included).
//  - DirectResidual: M qdd + C qd + g + f - tau from the Jacobi bank's estimates (differentiator_bank.hpp),
//    delayed like them by the bank's common delay; no dynamics of its own, but the noise of qdd.
//
// Fixed-size, allocation-free, no exceptions; a non-finite sample is reported and leaves the state as it was.
#include <Eigen/Core>
#include <array>

#include "jacobid/robot/joint_friction.hpp"
#include "jacobid/robot/rigid_body_terms.hpp"

namespace jacobid::robot {

enum class EstimatorStatus {
    Ok,
    NonFiniteInput,  // NaN or infinity in q, qd, qdd or tau: the sample is skipped
    InvalidGain,     // an observer gain <= 0 or a sample period <= 0
};

template <int N>
struct ExternalTorqueEstimate {
    JointVector<N> external = JointVector<N>::Zero();  // N.m (N for prismatic joints)
    JointVector<N> band = JointVector<N>::Zero();      // Coulomb band held at standstill (0 when moving)
    std::array<bool, N> standing{};
};

template <int N>
class MomentumObserver {
public:
    using Joints = JointVector<N>;

    // gain: K per joint, 1/s (the estimate's bandwidth); sample_period: T, s.
    MomentumObserver(const RigidBodyTerms<N>& terms, const JointFriction<N>& friction, const Joints& gain, double sample_period) noexcept
        : terms_(terms), friction_(friction), gain_(gain), period_(sample_period) {}

    EstimatorStatus valid() const noexcept {
        if (!(period_ > 0.0)) return EstimatorStatus::InvalidGain;
        for (int j = 0; j < terms_.joint_count(); ++j) {
            if (!(gain_[j] > 0.0)) return EstimatorStatus::InvalidGain;
        }
        return EstimatorStatus::Ok;
    }

    // Restarts at the next sample (its momentum becomes p0).
    void reset() noexcept {
        started_ = false;
        friction_.reset();
    }

    EstimatorStatus step(const Joints& q, const Joints& qd, const Joints& tau, ExternalTorqueEstimate<N>& out) noexcept {
        if (valid() != EstimatorStatus::Ok) return EstimatorStatus::InvalidGain;
        if (!q.allFinite() || !qd.allFinite() || !tau.allFinite()) return EstimatorStatus::NonFiniteInput;
        Joints p = Joints::Zero(), g = Joints::Zero(), ct = Joints::Zero(), f = Joints::Zero();
        terms_.momentum(q, qd, p);
        terms_.gravity(q, g);
        terms_.coriolis_transpose(q, qd, ct);
        friction_.step(q, qd, f, out.band, out.standing, &g);
        const Joints input = tau + ct - g - f;  // dp/dt = input + tau_ext
        if (!started_) {
            started_ = true;
            p0_ = p;
            integral_.setZero();
            feedback_.setZero();
            r_.setZero();
        } else {
            integral_ += 0.5 * period_ * (input + previous_input_);
        }
        previous_input_ = input;
        for (int j = 0; j < terms_.joint_count(); ++j) {
            r_[j] = gain_[j] * (p[j] - p0_[j] - integral_[j] - feedback_[j]) / (1.0 + gain_[j] * period_);
        }
        feedback_ += period_ * r_;
        out.external = r_;
        return EstimatorStatus::Ok;
    }

    const Joints& gain() const noexcept { return gain_; }
    double sample_period() const noexcept { return period_; }

private:
    const RigidBodyTerms<N>& terms_;
    JointFriction<N> friction_;
    Joints gain_;
    double period_ = 0.0;
    bool started_ = false;
    Joints p0_ = Joints::Zero(), integral_ = Joints::Zero(), feedback_ = Joints::Zero(), r_ = Joints::Zero();
    Joints previous_input_ = Joints::Zero();
};

template <int N>
class DirectResidual {
public:
    using Joints = JointVector<N>;

    DirectResidual(const RigidBodyTerms<N>& terms, const JointFriction<N>& friction) noexcept : terms_(terms), friction_(friction) {}

    void reset() noexcept { friction_.reset(); }

    EstimatorStatus step(const Joints& q, const Joints& qd, const Joints& qdd, const Joints& tau, ExternalTorqueEstimate<N>& out) noexcept {
        if (!q.allFinite() || !qd.allFinite() || !qdd.allFinite() || !tau.allFinite()) return EstimatorStatus::NonFiniteInput;
        Joints model = Joints::Zero(), f = Joints::Zero(), g = Joints::Zero();
        terms_.inverse_dynamics(q, qd, qdd, model);
        // One more Newton-Euler pass, only for a load-dependent Coulomb term.
        if (friction_.load_dependent()) terms_.gravity(q, g);
        friction_.step(q, qd, f, out.band, out.standing, &g);
        out.external = model + f - tau;  // M qdd + C qd + g + f = tau + tau_ext
        return EstimatorStatus::Ok;
    }

private:
    const RigidBodyTerms<N>& terms_;
    JointFriction<N> friction_;
};

}  // namespace jacobid::robot
