// SPDX-License-Identifier: MIT
// The lib's Newton-Euler regressor (rnea_regressor.hpp) against the closed-form planar 2R model of the
// paper (planar2r.hpp), an independent derivation: the 2R robot as an MDH chain (z axes vertical, link 1
// of length L1 along x) with random standard parameters. Its torques must equal the closed form's with
// the paper's base parameters ZZ1R = ZZ1 + L1^2 M2, ZZ2, MX2, MY2 (every other inertial parameter has no
// effect on a horizontal planar arm). Uses lib/ alone, so it also runs in the cross builds under
// qemu-user (scripts/cross-test.sh).
#include <gtest/gtest.h>

#include <random>

#include "jacobid/robot/mdh_joint.hpp"
#include "jacobid/robot/planar2r.hpp"
#include "jacobid/robot/rnea_regressor.hpp"

namespace {

using namespace jacobid::robot;

constexpr double kL1 = 0.5;

KinematicChain<2> planar2r_chain() {
    KinematicChain<2> chain;
    MdhJoint first;  // at the base
    MdhJoint second;
    second.antecedent = 0;
    second.d = kL1;
    EXPECT_EQ(chain.add(to_chain_joint(first)), ChainError::Ok);
    EXPECT_EQ(chain.add(to_chain_joint(second)), ChainError::Ok);
    return chain;
}

TEST(RneaRegressor, PlanarTwoLinkArmMatchesTheClosedFormModel) {
    StandardParameterOptions options;  // sign Coulomb friction, as Planar2RConfig's default
    const RneaRegressor<2> rnea(planar2r_chain(), Eigen::Vector3d(0.0, 0.0, -9.81), options);
    const Planar2R closed_form(Planar2RConfig{kL1, CoulombSign{}, false, false});
    const auto& layout = rnea.layout();
    ASSERT_EQ(rnea.parameter_count(), 2 * 12);  // XX..M, FV, FC per joint

    std::mt19937 rng(7);
    std::uniform_real_distribution<double> value(-2.0, 2.0);
    // Zero beyond the active columns (the regressors leave them untouched), so full fixed-size products work.
    RneaRegressor<2>::Regressor D = RneaRegressor<2>::Regressor::Zero();
    Planar2R::Regressor P = Planar2R::Regressor::Zero();
    for (int trial = 0; trial < 200; ++trial) {
        Eigen::Matrix<double, RneaRegressor<2>::kMaxParameters, 1> X = Eigen::Matrix<double, RneaRegressor<2>::kMaxParameters, 1>::Zero();
        for (int c = 0; c < rnea.parameter_count(); ++c) X[c] = value(rng);
        const auto standard = [&](int joint, ParameterKind kind) { return X[layout.column(joint, kind)]; };
        Eigen::Matrix<double, Planar2R::kMaxParameters, 1> base = Eigen::Matrix<double, Planar2R::kMaxParameters, 1>::Zero();
        base[closed_form.column(Planar2R::Parameter::ZZ1R)] = standard(0, ParameterKind::ZZ) + kL1 * kL1 * standard(1, ParameterKind::M);
        base[closed_form.column(Planar2R::Parameter::FV1)] = standard(0, ParameterKind::FV);
        base[closed_form.column(Planar2R::Parameter::FC1)] = standard(0, ParameterKind::FC);
        base[closed_form.column(Planar2R::Parameter::ZZ2)] = standard(1, ParameterKind::ZZ);
        base[closed_form.column(Planar2R::Parameter::MX2)] = standard(1, ParameterKind::MX);
        base[closed_form.column(Planar2R::Parameter::MY2)] = standard(1, ParameterKind::MY);
        base[closed_form.column(Planar2R::Parameter::FV2)] = standard(1, ParameterKind::FV);
        base[closed_form.column(Planar2R::Parameter::FC2)] = standard(1, ParameterKind::FC);

        const Eigen::Vector2d q(3.0 * value(rng), 3.0 * value(rng)), qd(value(rng), value(rng)), qdd(value(rng), value(rng));
        ASSERT_EQ(rnea.regressor(q, qd, qdd, D), RegressorStatus::Ok);
        closed_form.regressor(q, qd, qdd, P);
        const Eigen::Vector2d tau_rnea = D * X;
        const Eigen::Vector2d tau_closed = P * base;
        EXPECT_LT((tau_rnea - tau_closed).cwiseAbs().maxCoeff(), 1e-11) << "trial " << trial;
        // The O(n) recursion gives the same torques as the regressor.
        Eigen::Vector2d tau_direct;
        ASSERT_EQ(rnea.inverse_dynamics(q, qd, qdd, X, tau_direct), RegressorStatus::Ok);
        EXPECT_LT((tau_direct - tau_rnea).cwiseAbs().maxCoeff(), 1e-11) << "trial " << trial;
    }
}

TEST(RneaRegressor, NonFiniteJointStateIsRejected) {
    const RneaRegressor<2> rnea(planar2r_chain(), Eigen::Vector3d(0.0, 0.0, -9.81), StandardParameterOptions{});
    RneaRegressor<2>::Regressor D;
    const Eigen::Vector2d ok(0.1, 0.2), bad(0.1, std::nan(""));
    EXPECT_EQ(rnea.regressor(ok, bad, ok, D), RegressorStatus::NonFiniteInput);
    EXPECT_EQ(rnea.regressor(ok, ok, ok, D), RegressorStatus::Ok);
}

}  // namespace
