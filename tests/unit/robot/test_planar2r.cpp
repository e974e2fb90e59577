// SPDX-License-Identifier: MIT
// The 2R regressor against an independent computation of the same torques: Lagrange's equations applied
// to the kinetic energy of the two rigid bodies (masses, centres of mass, central inertias, rotor
// inertias), with the body velocities from screw kinematics (v = sum qd_i z x (p - o_i)) rather than from
// the closed-form model. Derivatives are exact to rounding: M(q) by polarization of the quadratic form
// T(q, qd), d/dq by complex-step differentiation, so the comparison holds to 1e-9.
#include <gtest/gtest.h>

#include <complex>
#include <random>

#include "jacobid/robot/planar2r.hpp"

namespace {

using jacobid::robot::CoulombModel;
using jacobid::robot::CoulombSign;
using jacobid::robot::Planar2R;
using jacobid::robot::Planar2RConfig;
using Complex = std::complex<double>;

struct PhysicalRobot {
    double L1 = 0.5;
    double m1 = 7.0, c1x = 0.21, c1y = -0.03, I1c = 0.3, Ia1 = 1.1;
    double m2 = 2.3, c2x = 0.11, c2y = 0.017, I2c = 0.02, Ia2 = 0.013;
};

// Kinetic energy; q may be complex (complex step), qd is real.
template <typename S>
S kinetic_energy(const PhysicalRobot& r, const S q[2], const double qd[2], bool with_rotor2) {
    using std::cos;
    using std::sin;
    // Body 1: centre of mass p1 = Rot(q1) c1, joint 1 at the origin.
    const S p1x = cos(q[0]) * r.c1x - sin(q[0]) * r.c1y;
    const S p1y = sin(q[0]) * r.c1x + cos(q[0]) * r.c1y;
    const S v1x = -qd[0] * p1y;
    const S v1y = qd[0] * p1x;
    // Body 2: joint 2 at o2 = L1 (cos q1, sin q1), centre of mass p2 = o2 + Rot(q1 + q2) c2.
    const S o2x = r.L1 * cos(q[0]);
    const S o2y = r.L1 * sin(q[0]);
    const S a = q[0] + q[1];
    const S p2x = o2x + cos(a) * r.c2x - sin(a) * r.c2y;
    const S p2y = o2y + sin(a) * r.c2x + cos(a) * r.c2y;
    const S v2x = -qd[0] * p2y - qd[1] * (p2y - o2y);
    const S v2y = qd[0] * p2x + qd[1] * (p2x - o2x);
    const double w2 = qd[0] + qd[1];
    S t = 0.5 * r.m1 * (v1x * v1x + v1y * v1y) + 0.5 * r.I1c * qd[0] * qd[0] + 0.5 * r.Ia1 * qd[0] * qd[0];
    t += 0.5 * r.m2 * (v2x * v2x + v2y * v2y) + 0.5 * r.I2c * w2 * w2;
    if (with_rotor2) t += 0.5 * r.Ia2 * qd[1] * qd[1];
    return t;
}

// Inertia matrix entry M_ij(q) by polarization of T(q, .) (exact for a quadratic form).
template <typename S>
S inertia(const PhysicalRobot& r, const S q[2], int i, int j, bool rotor) {
    double ei[2] = {0, 0}, ej[2] = {0, 0}, eij[2] = {0, 0};
    ei[i] = 1;
    ej[j] = 1;
    eij[i] += 1;
    eij[j] += 1;
    if (i == j) return 2.0 * kinetic_energy(r, q, ei, rotor);
    return kinetic_energy(r, q, eij, rotor) - kinetic_energy(r, q, ei, rotor) - kinetic_energy(r, q, ej, rotor);
}

constexpr double kStep = 1e-30;

// Lagrange: tau_i = sum_j M_ij qdd_j + sum_jk dM_ij/dq_k qd_k qd_j - dT/dq_i (+ friction).
void lagrange_torques(const PhysicalRobot& r, const double q[2], const double qd[2], const double qdd[2], bool rotor, double tau[2]) {
    const Complex qc[2] = {q[0], q[1]};
    for (int i = 0; i < 2; ++i) {
        double t = 0.0;
        for (int j = 0; j < 2; ++j) {
            t += inertia(r, qc, i, j, rotor).real() * qdd[j];
            for (int k = 0; k < 2; ++k) {
                Complex qk[2] = {q[0], q[1]};
                qk[k] += Complex(0.0, kStep);
                t += inertia(r, qk, i, j, rotor).imag() / kStep * qd[k] * qd[j];
            }
        }
        Complex qi[2] = {q[0], q[1]};
        qi[i] += Complex(0.0, kStep);
        t -= kinetic_energy(r, qi, qd, rotor).imag() / kStep;
        tau[i] = t;
    }
}

struct Friction {
    double fv[2] = {0.25, 0.014};
    double fc[2] = {0.43, 0.127};
    double off[2] = {0.07, -0.02};
};

// Base parameters from the physical ones (the regrouping of docs/method.md, "The planar 2R robot").
std::vector<double> base_parameters(const Planar2R& model, const PhysicalRobot& r, const Friction& f) {
    using P = Planar2R::Parameter;
    std::vector<double> x(static_cast<std::size_t>(model.parameter_count()), 0.0);
    auto put = [&](P p, double v) {
        if (model.column(p) >= 0) x[static_cast<std::size_t>(model.column(p))] = v;
    };
    const double zz1 = r.I1c + r.m1 * (r.c1x * r.c1x + r.c1y * r.c1y);
    put(P::ZZ1R, zz1 + r.Ia1 + r.m2 * r.L1 * r.L1);
    put(P::ZZ2, r.I2c + r.m2 * (r.c2x * r.c2x + r.c2y * r.c2y));
    put(P::MX2, r.m2 * r.c2x);
    put(P::MY2, r.m2 * r.c2y);
    put(P::IA2, r.Ia2);
    put(P::FV1, f.fv[0]);
    put(P::FC1, f.fc[0]);
    put(P::FOFF1, f.off[0]);
    put(P::FV2, f.fv[1]);
    put(P::FC2, f.fc[1]);
    put(P::FOFF2, f.off[1]);
    return x;
}

void check_against_lagrange(const Planar2RConfig& config) {
    const Planar2R model(config);
    PhysicalRobot r;
    r.L1 = config.L1;
    const Friction f;
    const std::vector<double> x = base_parameters(model, r, f);
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> pos(-3.0, 3.0), vel(-4.0, 4.0), acc(-30.0, 30.0);
    for (int trial = 0; trial < 200; ++trial) {
        const double q[2] = {pos(rng), pos(rng)};
        double qd[2] = {vel(rng), vel(rng)};
        if (trial == 0) qd[0] = qd[1] = 0.0;  // sign(0) = 0 and atan(0) = 0: only inertia and offsets remain
        const double qdd[2] = {acc(rng), acc(rng)};
        double tau[2];
        lagrange_torques(r, q, qd, qdd, config.rotor_inertia, tau);
        for (int j = 0; j < 2; ++j) {
            tau[j] += f.fv[j] * qd[j] + f.fc[j] * config.coulomb(qd[j]) + (config.friction_offset ? f.off[j] : 0.0);
        }
        Planar2R::Regressor D = Planar2R::Regressor::Constant(std::nan(""));
        model.regressor({q[0], q[1]}, {qd[0], qd[1]}, {qdd[0], qdd[1]}, D);
        for (int j = 0; j < 2; ++j) {
            double predicted = 0.0;
            for (int c = 0; c < model.parameter_count(); ++c) predicted += D(j, c) * x[static_cast<std::size_t>(c)];
            EXPECT_NEAR(predicted, tau[j], 1e-9) << "trial " << trial << " joint " << j + 1;
        }
    }
}

TEST(Planar2R, PaperBaseParametersInPaperOrder) {
    const Planar2R model;
    ASSERT_EQ(model.parameter_count(), 8);
    const char* expected[] = {"ZZ1R", "FV1", "FC1", "ZZ2", "MX2", "MY2", "FV2", "FC2"};
    for (int c = 0; c < 8; ++c) EXPECT_STREQ(model.parameter_name(c), expected[c]);
}

TEST(Planar2R, OptionalColumnsAreInsertedNextToTheirJoint) {
    Planar2RConfig config;
    config.friction_offset = true;
    config.rotor_inertia = true;
    const Planar2R model(config);
    ASSERT_EQ(model.parameter_count(), 11);
    const char* expected[] = {"ZZ1R", "FV1", "FC1", "FOFF1", "ZZ2", "MX2", "MY2", "IA2", "FV2", "FC2", "FOFF2"};
    for (int c = 0; c < 11; ++c) EXPECT_STREQ(model.parameter_name(c), expected[c]);
}

TEST(Planar2R, MatchesLagrangeWithSignFriction) { check_against_lagrange({}); }

TEST(Planar2R, MatchesLagrangeWithSmoothFrictionOffsetsRotorAndOtherL1) {
    Planar2RConfig config;
    config.L1 = 0.83;
    config.coulomb = CoulombSign{CoulombModel::SmoothAtan, 40.0};
    config.friction_offset = true;
    config.rotor_inertia = true;
    check_against_lagrange(config);
}

TEST(CoulombSign, SmoothSignApproachesSignAndIsOdd) {
    const CoulombSign smooth{CoulombModel::SmoothAtan, 100.0};
    EXPECT_DOUBLE_EQ(smooth(0.0), 0.0);
    EXPECT_NEAR(smooth(10.0), 1.0, 1e-3);  // 2/pi atan(1000) = 1 - 6.4e-4
    EXPECT_DOUBLE_EQ(smooth(-0.3), -smooth(0.3));
    EXPECT_NEAR(smooth(0.01), 0.5, 1e-12);  // atan(1) = pi/4
    const CoulombSign sign{};
    EXPECT_EQ(sign(-1e-12), -1.0);
    EXPECT_EQ(sign(0.0), 0.0);
}

}  // namespace
