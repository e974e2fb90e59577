// SPDX-License-Identifier: MIT
// The external-torque estimators of lib/include/jacobid/robot/external_torque.hpp against an independent
// truth: a PUMA-like arm integrated with Featherstone's articulated-body algorithm (articulated_body.hpp, not
// the Newton-Euler recursion the estimators use), an external torque pulse applied to the physics. In
// continuous time the momentum observer's r is tau_ext through dr/dt = K (tau_ext - r), so r is held to that
// first-order response of the true pulse; the direct residual with the true acceleration is tau_ext itself.
// Also: the standstill band (friction holds a torque inside it: no alarm), and no allocation per sample.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "allocation_counter.hpp"
#include "jacobid/robot/articulated_body.hpp"
#include "jacobid/robot/contact_detector.hpp"
#include "jacobid/robot/external_torque.hpp"
#include "jacobid/robot/mdh_joint.hpp"

namespace {

using namespace jacobid::robot;
constexpr int kN = 6;
using Joints = JointVector<kN>;
using Parameters = RneaRegressor<kN>::Parameters;

KinematicChain<kN> puma_like_chain() {
    const double h = 1.5707963267948966;
    const MdhJoint rows[kN] = {{JointType::Revolute, -1, 0, 0, 0, 0},          {JointType::Revolute, 0, -h, 0, 0, 0.2435},
                               {JointType::Revolute, 1, 0, 0.4318, 0, -0.0934}, {JointType::Revolute, 2, h, -0.0203, 0, 0.4331},
                               {JointType::Revolute, 3, -h, 0, 0, 0},           {JointType::Revolute, 4, h, 0, 0, 0}};
    KinematicChain<kN> chain;
    for (const auto& row : rows) EXPECT_EQ(chain.add(to_chain_joint(row)), ChainError::Ok);
    return chain;
}

StandardParameterOptions options() {
    StandardParameterOptions o;
    o.rotor_inertia = true;
    o.friction_offset = true;
    o.coulomb = {CoulombModel::SmoothAtan, 50.0};
    return o;
}

// Physically consistent links (inertia about the centre of mass shifted to the link origin), rotor
// inertias and friction, all different per joint.
Parameters parameters(const StandardParameterLayout<kN>& layout) {
    Parameters X = Parameters::Zero();
    const double mass[kN] = {10.0, 17.0, 4.8, 0.8, 0.35, 0.1};
    for (int j = 0; j < kN; ++j) {
        const Eigen::Vector3d c(0.02 * (j + 1), -0.01 * j, 0.05 - 0.01 * j);
        const Eigen::Matrix3d Ic = Eigen::Vector3d(0.3, 0.25, 0.2).asDiagonal() * (mass[j] * 0.05);
        const Eigen::Matrix3d Io = Ic + mass[j] * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
        auto set = [&](ParameterKind kind, double v) { X[layout.column(j, kind)] = v; };
        set(ParameterKind::XX, Io(0, 0));
        set(ParameterKind::XY, Io(0, 1));
        set(ParameterKind::XZ, Io(0, 2));
        set(ParameterKind::YY, Io(1, 1));
        set(ParameterKind::YZ, Io(1, 2));
        set(ParameterKind::ZZ, Io(2, 2));
        set(ParameterKind::MX, mass[j] * c.x());
        set(ParameterKind::MY, mass[j] * c.y());
        set(ParameterKind::MZ, mass[j] * c.z());
        set(ParameterKind::M, mass[j]);
        set(ParameterKind::IA, 0.05 / (j + 1));
        set(ParameterKind::FV, 0.8 / (j + 1));
        set(ParameterKind::FC, 2.0 / (j + 1));
        set(ParameterKind::FOFF, 0.1 * (j - 2));
    }
    return X;
}

struct Arm {
    RneaRegressor<kN> regressor{puma_like_chain(), Eigen::Vector3d(0, 0, -9.81), options()};
    Parameters X = parameters(regressor.layout());
    ArticulatedBody<kN> body{regressor.chain(), regressor.gravity()};
    Arm() { body.set_standard_parameters(regressor.layout(), X); }

    // The true friction the physics feels (the identified model's, moving everywhere).
    Joints friction(const Joints& qd) const {
        Joints f;
        for (int j = 0; j < kN; ++j) {
            const auto& l = regressor.layout();
            f[j] = X[l.column(j, ParameterKind::FV)] * qd[j] + X[l.column(j, ParameterKind::FC)] * regressor.coulomb(j)(qd[j]) +
                   X[l.column(j, ParameterKind::FOFF)];
        }
        return f;
    }
    Joints accelerations(const Joints& q, const Joints& qd, const Joints& tau_motor, const Joints& tau_external) const {
        ArticulatedBodyData<kN> data;
        Joints qdd;
        EXPECT_EQ(body.forward_dynamics(q, qd, tau_motor + tau_external - friction(qd), data, qdd), ArticulatedBodyStatus::Ok);
        return qdd;
    }
};

constexpr double kPulseStart = 1.0, kPulseEnd = 1.6, kPulse = 6.0;  // s, s, N.m
constexpr int kPulseJoint = 1;

Joints external_at(double t) {
    Joints e = Joints::Zero();
    if (t >= kPulseStart && t < kPulseEnd) e[kPulseJoint] = kPulse;
    return e;
}

// The true first-order response of r to the pulse: dr/dt = K (tau_ext - r), r(0) = 0.
double observer_truth(double t, double K) {
    if (t < kPulseStart) return 0.0;
    const double rise = kPulse * (1.0 - std::exp(-K * (std::min(t, kPulseEnd) - kPulseStart)));
    return t < kPulseEnd ? rise : rise * std::exp(-K * (t - kPulseEnd));
}

// PD tracking of sines at 1 kHz, physics by RK4 at 10 kHz. As in the host simulator (sim/closed_loop.hpp), the
// drive ramps each command linearly over one control period (one period of latency): the motor torque is
// continuous, and the torque logged at t_k is the one acting at t_k.
template <typename Sink>
void simulate(const Arm& arm, double duration, Sink&& sink) {
    const double control = 1e-3;
    const int substeps = 10;
    const double h = control / substeps;
    Joints q = Joints::Zero(), qd = Joints::Zero();
    for (int j = 0; j < kN; ++j) q[j] = 0.1 * j;
    const Joints q0 = q;
    Joints u_prev = Joints::Zero();
    arm.regressor.inverse_dynamics(q, Joints::Zero(), Joints::Zero(), arm.X, u_prev);  // at rest, holding gravity
    for (int k = 0; k * control <= duration; ++k) {
        const double t = k * control;
        Joints u;
        for (int j = 0; j < kN; ++j) {
            const double w = 2.0 + 0.7 * j;  // rad/s
            const double ref = q0[j] + 0.4 * std::sin(w * t), ref_d = 0.4 * w * std::cos(w * t);
            u[j] = 400.0 / (j + 1) * (ref - q[j]) + 40.0 / (j + 1) * (ref_d - qd[j]);
        }
        Joints g;
        arm.regressor.inverse_dynamics(q, Joints::Zero(), Joints::Zero(), arm.X, g);
        u += g;  // gravity compensation (with the friction offset, constant: harmless)
        sink(t, q, qd, arm.accelerations(q, qd, u_prev, external_at(t)), u_prev);
        auto torque = [&](double at) -> Joints { return u_prev + (at - t) / control * (u - u_prev); };
        for (int s = 0; s < substeps; ++s) {
            const double ts = t + s * h;
            auto f = [&](double at, const Joints& qs, const Joints& qds) { return arm.accelerations(qs, qds, torque(at), external_at(at)); };
            const Joints k1v = f(ts, q, qd), k1q = qd;
            const Joints k2v = f(ts + 0.5 * h, q + 0.5 * h * k1q, qd + 0.5 * h * k1v), k2q = qd + 0.5 * h * k1v;
            const Joints k3v = f(ts + 0.5 * h, q + 0.5 * h * k2q, qd + 0.5 * h * k2v), k3q = qd + 0.5 * h * k2v;
            const Joints k4v = f(ts + h, q + h * k3q, qd + h * k3v), k4q = qd + h * k3v;
            q += h / 6.0 * (k1q + 2 * k2q + 2 * k3q + k4q);
            qd += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
        }
        u_prev = u;
    }
}

TEST(MomentumObserver, FollowsTheFirstOrderResponseOfTheTrueExternalTorque) {
    const Arm arm;
    const RigidBodyTerms<kN> terms(arm.regressor, arm.X);
    const double K = 100.0;
    MomentumObserver<kN> observer(terms, JointFriction<kN>(arm.regressor, arm.X), Joints::Constant(K), 1e-3);
    ExternalTorqueEstimate<kN> e;
    double worst = 0.0, worst_other = 0.0;
    simulate(arm, 2.5, [&](double t, const Joints& q, const Joints& qd, const Joints&, const Joints& tau) {
        ASSERT_EQ(observer.step(q, qd, tau, e), EstimatorStatus::Ok);
        worst = std::max(worst, std::abs(e.external[kPulseJoint] - observer_truth(t, K)));
        for (int j = 0; j < kN; ++j) {
            if (j != kPulseJoint) worst_other = std::max(worst_other, std::abs(e.external[j]));
        }
    });
    // The discretisation (torque held over 1 ms, trapezoid integral, backward Euler feedback) costs a few
    // tenths of a step of the 6 N.m pulse at the edges; elsewhere the estimate is the truth.
    EXPECT_LT(worst, 0.05 * kPulse);
    EXPECT_LT(worst_other, 0.02 * kPulse);
}

TEST(MomentumObserver, SettlesOnThePulseAmplitude) {
    const Arm arm;
    const RigidBodyTerms<kN> terms(arm.regressor, arm.X);
    MomentumObserver<kN> observer(terms, JointFriction<kN>(arm.regressor, arm.X), Joints::Constant(100.0), 1e-3);
    ExternalTorqueEstimate<kN> e;
    double at_end = 0.0;
    simulate(arm, 1.59, [&](double, const Joints& q, const Joints& qd, const Joints&, const Joints& tau) {
        observer.step(q, qd, tau, e);
        at_end = e.external[kPulseJoint];
    });
    EXPECT_NEAR(at_end, kPulse, 0.01 * kPulse);  // 0.59 s = 59 time constants after the onset
}

TEST(DirectResidual, IsTheExternalTorqueWithTheTrueAcceleration) {
    const Arm arm;
    const RigidBodyTerms<kN> terms(arm.regressor, arm.X);
    DirectResidual<kN> residual(terms, JointFriction<kN>(arm.regressor, arm.X));
    ExternalTorqueEstimate<kN> e;
    double worst = 0.0;
    simulate(arm, 2.0, [&](double t, const Joints& q, const Joints& qd, const Joints& qdd, const Joints& tau) {
        ASSERT_EQ(residual.step(q, qd, qdd, tau, e), EstimatorStatus::Ok);
        worst = std::max(worst, (e.external - external_at(t)).cwiseAbs().maxCoeff());
    });
    EXPECT_LT(worst, 1e-9);
}

TEST(RigidBodyTerms, CoriolisTransposeSatisfiesTheMomentumBalance) {
    // dp/dt = tau_rigid + C^T qd - g for the rigid body alone (no friction, no external torque): the
    // momentum's central difference along a simulated motion against the right-hand side.
    const Arm arm;
    const RigidBodyTerms<kN> terms(arm.regressor, arm.X);
    Joints q, qd, qdd;
    for (int j = 0; j < kN; ++j) q[j] = 0.3 * j - 0.5, qd[j] = 0.8 - 0.25 * j, qdd[j] = 1.5 * std::cos(j);
    Joints tau, g, ct;
    terms.inverse_dynamics(q, qd, qdd, tau);
    terms.gravity(q, g);
    terms.coriolis_transpose(q, qd, ct);
    const double dt = 1e-5;
    Joints p_ahead, p_behind;
    terms.momentum(q + dt * qd + 0.5 * dt * dt * qdd, qd + dt * qdd, p_ahead);
    terms.momentum(q - dt * qd + 0.5 * dt * dt * qdd, qd - dt * qdd, p_behind);
    const Joints pdot = (p_ahead - p_behind) / (2 * dt);
    for (int j = 0; j < kN; ++j) EXPECT_NEAR(pdot[j], tau[j] + ct[j] - g[j], 1e-6 * (1.0 + std::abs(tau[j])));
}

// The standstill tests' pose (q_j = 0.2 j), the torque that holds the arm still there (gravity and FOFF), and a
// detector with thresholds 0.5 N.m moving, 0.3 N.m beyond the band standing.
struct RestingPose {
    Joints q, g;
    ContactDetector<kN> detector;
    explicit RestingPose(const Arm& arm) {
        for (int j = 0; j < kN; ++j) q[j] = 0.2 * j;
        arm.regressor.inverse_dynamics(q, Joints::Zero(), Joints::Zero(), arm.X, g);
        for (int j = 0; j < kN; ++j) detector.set_joint(j, {0.5, 0.3});
    }
};

TEST(ContactDetector, TorqueInsideTheCoulombBandAtStandstillIsNoContact) {
    // The arm at rest: the motor holds gravity plus x; friction holds any x inside the band [-FC, FC].
    const Arm arm;
    const RigidBodyTerms<kN> terms(arm.regressor, arm.X);
    JointFriction<kN> friction(arm.regressor, arm.X);
    DirectResidual<kN> residual(terms, friction);
    RestingPose rest(arm);
    const Joints& q = rest.q;
    const Joints& g = rest.g;
    ContactDetector<kN>& detector = rest.detector;
    // The articulated-body side agrees that this torque holds the arm still.
    EXPECT_LT(arm.accelerations(q, Joints::Zero(), g, Joints::Zero()).norm(), 1e-9);
    ExternalTorqueEstimate<kN> e;
    const double fc1 = arm.X[arm.regressor.layout().column(1, ParameterKind::FC)];
    for (const double x : {0.9 * fc1, -0.9 * fc1, 0.99 * (fc1 + 0.3)}) {
        Joints tau = g;
        tau[1] += x;
        ASSERT_EQ(residual.step(q, Joints::Zero(), Joints::Zero(), tau, e), EstimatorStatus::Ok);
        EXPECT_TRUE(e.standing[1]);
        EXPECT_DOUBLE_EQ(e.band[1], fc1);
        EXPECT_NEAR(e.external[1], -x, 1e-9);
        EXPECT_EQ(detector.detect(e, kN), 0u) << x;
    }
    Joints tau = g;
    tau[1] += 1.01 * (fc1 + 0.3);
    residual.step(q, Joints::Zero(), Joints::Zero(), tau, e);
    EXPECT_EQ(detector.detect(e, kN), 1u << 1);
    // Moving, the band is gone: the moving threshold alone.
    Joints qd = Joints::Zero();
    qd[1] = 0.5;
    residual.step(q, qd, Joints::Zero(), tau, e);
    EXPECT_FALSE(e.standing[1]);
    EXPECT_DOUBLE_EQ(detector.threshold(e, 1), 0.5);
}

TEST(ContactDetector, BandMarginWidensTheStandstillBandAboveTheCoulombLevel) {
    // A joint breaks away above its sliding Coulomb level: with band_margin 0.2 it holds up to 1.2 FC at rest.
    const Arm arm;
    const RigidBodyTerms<kN> terms(arm.regressor, arm.X);
    JointFriction<kN> friction(arm.regressor, arm.X);
    JointFrictionParameters p = friction.joint(1);
    p.band_margin = 0.2;
    friction.set_joint(1, p);
    DirectResidual<kN> residual(terms, friction);
    const RestingPose rest(arm);
    const double fc1 = arm.X[arm.regressor.layout().column(1, ParameterKind::FC)];
    ExternalTorqueEstimate<kN> e;
    for (const double x : {1.15 * fc1, -1.15 * fc1, 1.01 * (1.2 * fc1 + 0.3)}) {
        Joints tau = rest.g;
        tau[1] += x;
        ASSERT_EQ(residual.step(rest.q, Joints::Zero(), Joints::Zero(), tau, e), EstimatorStatus::Ok);
        EXPECT_NEAR(e.band[1], 1.2 * fc1, 1e-12);
        EXPECT_NEAR(e.band[2], arm.X[arm.regressor.layout().column(2, ParameterKind::FC)], 1e-12);  // the others keep FC
        EXPECT_EQ(rest.detector.detect(e, kN), std::abs(x) > 1.2 * fc1 + 0.3 ? 1u << 1 : 0u) << x;
    }
}

TEST(ContactDetector, ConfirmsAContactAfterTheGivenNumberOfConsecutiveSamples) {
    ContactDetector<kN> detector;
    detector.set_confirm(3);
    const std::uint32_t contact = 1u << 2;
    // One sample and two samples over the threshold (glitches), then a contact of four samples.
    const std::uint32_t masks[] = {contact, 0, contact, contact, 0, contact, contact, contact, contact, 0};
    const bool expected[] = {false, false, false, false, false, false, false, true, true, false};
    for (std::size_t k = 0; k < std::size(masks); ++k) EXPECT_EQ(detector.confirmed(masks[k]), expected[k]) << k;
}

TEST(ExternalTorque, NonFiniteSamplesAndInvalidGainsAreRefused) {
    const Arm arm;
    const RigidBodyTerms<kN> terms(arm.regressor, arm.X);
    const JointFriction<kN> friction(arm.regressor, arm.X);
    ExternalTorqueEstimate<kN> e;
    MomentumObserver<kN> bad_gain(terms, friction, Joints::Zero(), 1e-3);
    EXPECT_EQ(bad_gain.step(Joints::Zero(), Joints::Zero(), Joints::Zero(), e), EstimatorStatus::InvalidGain);
    MomentumObserver<kN> observer(terms, friction, Joints::Constant(50.0), 1e-3);
    Joints nan = Joints::Zero();
    nan[2] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(observer.step(nan, Joints::Zero(), Joints::Zero(), e), EstimatorStatus::NonFiniteInput);
    DirectResidual<kN> residual(terms, friction);
    EXPECT_EQ(residual.step(Joints::Zero(), Joints::Zero(), nan, Joints::Zero(), e), EstimatorStatus::NonFiniteInput);
}

TEST(ExternalTorque, NoAllocationPerSample) {
    const Arm arm;
    const RigidBodyTerms<kN> terms(arm.regressor, arm.X);
    const JointFriction<kN> friction(arm.regressor, arm.X);
    MomentumObserver<kN> observer(terms, friction, Joints::Constant(50.0), 1e-3);
    DirectResidual<kN> residual(terms, friction);
    ContactDetector<kN> detector;
    ExternalTorqueEstimate<kN> e;
    Joints q, qd, qdd, tau;
    std::uint32_t any = 0;
    const auto before = jacobid::test::allocation_count();
    for (int k = 0; k < 1000; ++k) {
        q.setConstant(0.001 * k);
        qd.setConstant(0.5 * std::sin(0.01 * k));
        qdd.setConstant(-0.3);
        tau.setConstant(2.0);
        observer.step(q, qd, tau, e);
        any |= detector.detect(e, kN);
        residual.step(q, qd, qdd, tau, e);
        any |= detector.detect(e, kN);
    }
    EXPECT_EQ(jacobid::test::allocation_count(), before);
    EXPECT_NE(any, 0u);  // thresholds 0: the loop did run the detector
}

}  // namespace
