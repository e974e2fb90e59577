// SPDX-License-Identifier: MIT
// The fixed-size RNEA regressor allocates nothing per sample (project rule for lib/), rejects non-finite
// input with a result value instead of producing NaN rows, and its O(n) inverse dynamics is the same
// model: tau = W X for any parameter vector (W itself is checked against KDL in test_rnea_vs_kdl.cpp).
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "allocation_counter.hpp"
#include "jacobid/robot/mdh_joint.hpp"
#include "jacobid/robot/rnea_regressor.hpp"

namespace {

using namespace jacobid::robot;

KinematicChain<6> puma_like_chain() {
    const double h = 1.5707963267948966;
    const MdhJoint rows[6] = {{JointType::Revolute, -1, 0, 0, 0, 0},       {JointType::Revolute, 0, -h, 0, 0, 0.2435},
                              {JointType::Revolute, 1, 0, 0.4318, 0, -0.0934}, {JointType::Revolute, 2, h, -0.0203, 0, 0.4331},
                              {JointType::Revolute, 3, -h, 0, 0, 0},        {JointType::Revolute, 4, h, 0, 0, 0}};
    KinematicChain<6> chain;
    for (const auto& row : rows) EXPECT_EQ(chain.add(to_chain_joint(row)), ChainError::Ok);
    return chain;
}

TEST(RneaRegressor, NoAllocationPerSample) {
    StandardParameterOptions options;
    options.rotor_inertia = true;
    const RneaRegressor<6> regressor(puma_like_chain(), Eigen::Vector3d(0, 0, -9.81), options);
    RneaRegressor<6>::Regressor D;
    RneaRegressor<6>::Joints q, qd, qdd;
    const auto before = jacobid::test::allocation_count();
    double sum = 0.0;
    for (int k = 0; k < 1000; ++k) {
        q.setConstant(0.001 * k);
        qd.setConstant(0.5);
        qdd.setConstant(-0.3);
        ASSERT_EQ(regressor.regressor(q, qd, qdd, D), RegressorStatus::Ok);
        sum += D(1, 20);
    }
    EXPECT_EQ(jacobid::test::allocation_count(), before);
    EXPECT_TRUE(std::isfinite(sum));
}

TEST(RneaRegressor, InverseDynamicsEqualsRegressorTimesParametersWithoutAllocating) {
    StandardParameterOptions options;
    options.rotor_inertia = true;
    options.friction_offset = true;
    options.coulomb.model = CoulombModel::SmoothAtan;
    const RneaRegressor<6> regressor(puma_like_chain(), Eigen::Vector3d(0.5, -0.2, -9.81), options);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    RneaRegressor<6>::Parameters X = RneaRegressor<6>::Parameters::Zero();
    for (int c = 0; c < regressor.parameter_count(); ++c) X[c] = u(rng);
    RneaRegressor<6>::Regressor D;
    RneaRegressor<6>::Joints q, qd, qdd, tau;
    for (int trial = 0; trial < 200; ++trial) {
        for (int j = 0; j < 6; ++j) q[j] = 3 * u(rng), qd[j] = 2 * u(rng), qdd[j] = 5 * u(rng);
        ASSERT_EQ(regressor.regressor(q, qd, qdd, D), RegressorStatus::Ok);
        const auto before = jacobid::test::allocation_count();
        ASSERT_EQ(regressor.inverse_dynamics(q, qd, qdd, X, tau), RegressorStatus::Ok);
        EXPECT_EQ(jacobid::test::allocation_count(), before);
        const RneaRegressor<6>::Joints reference = D * X;
        for (int j = 0; j < 6; ++j) EXPECT_NEAR(tau[j], reference[j], 1e-12 * std::max(1.0, std::abs(reference[j])));
    }
}

TEST(RneaRegressor, RejectsNonFiniteStateAndInvalidChains) {
    const RneaRegressor<6> regressor(puma_like_chain(), Eigen::Vector3d(0, 0, -9.81), {});
    RneaRegressor<6>::Regressor D;
    RneaRegressor<6>::Joints q = RneaRegressor<6>::Joints::Zero(), qd = q, qdd = q;
    qd[3] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(regressor.regressor(q, qd, qdd, D), RegressorStatus::NonFiniteInput);

    KinematicChain<2> chain;
    ChainJoint joint;
    joint.antecedent = 0;  // no joint 0 yet
    EXPECT_EQ(chain.add(joint), ChainError::BadAntecedent);
    joint.antecedent = -1;
    joint.axis.setZero();
    EXPECT_EQ(chain.add(joint), ChainError::ZeroAxis);
    joint.axis = Eigen::Vector3d::UnitX();
    joint.rotation(0, 0) = -1.0;  // a reflection
    EXPECT_EQ(chain.add(joint), ChainError::NotARotation);
    joint.rotation.setIdentity();
    EXPECT_EQ(chain.add(joint), ChainError::Ok);
    EXPECT_EQ(chain.add(joint), ChainError::Ok);
    EXPECT_EQ(chain.add(joint), ChainError::TooManyJoints);
}

}  // namespace
