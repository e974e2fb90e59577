// SPDX-License-Identifier: MIT
// The RNEA standard-parameter regressor against an independent implementation of inverse dynamics:
// orocos-kdl's ChainIdSolver_RNE (Debian liborocos-kdl-dev), which works on spatial inertias and frames
// and shares no code with ours. For the PUMA 560 and the UR5-like arm, with random standard inertial
// parameters, W(q, qd, qdd) X must equal KDL's torques to 1e-9 over random states. KDL has no friction and
// no rotor inertia: those columns are checked against their definitions (IAj qdd_j, FVj qd_j, FCj sign).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kdl_reference.hpp"
#include "serial_test_support.hpp"

namespace {

using namespace jacobid;
using robot::ParameterKind;

void compare_with_kdl(const std::string& file) {
    const auto description = robot::load_robot_description(test::example_robot(file));
    const auto config = test::serial_config(description);
    const robot::SerialRobotModel model(config);
    const int n = model.joint_count();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    // Random standard parameters: masses positive, everything else of either sign (KDL only does algebra).
    Eigen::VectorXd x = Eigen::VectorXd::Zero(model.standard_parameter_count());
    for (int c = 0; c < x.size(); ++c) {
        const std::string& name = model.standard_names()[static_cast<std::size_t>(c)];
        if (name.rfind("IA", 0) == 0 || name.rfind("FV", 0) == 0 || name.rfind("FC", 0) == 0 || name.rfind("FOFF", 0) == 0) continue;
        x[c] = name[0] == 'M' && name[1] != 'X' && name[1] != 'Y' && name[1] != 'Z' ? 1.0 + 4.0 * std::abs(u(rng)) : u(rng);
    }
    std::vector<test::LinkInertial> links(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) {
        for (int k = 0; k < robot::kInertialKinds; ++k) {
            const auto kind = static_cast<ParameterKind>(k);
            links[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)] = x[model.standard_index(robot::kind_name(kind) + std::to_string(j + 1))];
        }
    }
    const KDL::Chain chain = test::kdl_chain(config, links);
    Eigen::MatrixXd W(n, model.standard_parameter_count());
    KDL::JntArray q(static_cast<unsigned>(n)), qd(q), qdd(q);
    double worst = 0.0;
    for (int trial = 0; trial < 200; ++trial) {
        for (int j = 0; j < n; ++j) {
            q(static_cast<unsigned>(j)) = 3.0 * u(rng);
            qd(static_cast<unsigned>(j)) = 2.0 * u(rng);
            qdd(static_cast<unsigned>(j)) = 5.0 * u(rng);
        }
        model.standard_regressor(q.data.data(), qd.data.data(), qdd.data.data(), W);
        const Eigen::VectorXd tau = test::kdl_torques(chain, config.gravity, q, qd, qdd);
        const Eigen::VectorXd ours = W * x;
        for (int j = 0; j < n; ++j) {
            const double reference = tau[j];
            worst = std::max(worst, std::abs(ours[j] - reference) / std::max(1.0, std::abs(reference)));
            ASSERT_NEAR(ours[j], reference, 1e-9 * std::max(1.0, std::abs(reference))) << file << " joint " << j + 1 << " trial " << trial;
        }
        // Rotor inertia and friction act on their own joint only, by definition.
        for (int j = 0; j < n; ++j) {
            const auto J = std::to_string(j + 1);
            for (int row = 0; row < n; ++row) {
                const double own = row == j ? 1.0 : 0.0;
                const int ia = model.standard_index("IA" + J);
                if (ia >= 0) {
                    EXPECT_EQ(W(row, ia), own * qdd(static_cast<unsigned>(j)));
                }
                EXPECT_EQ(W(row, model.standard_index("FV" + J)), own * qd(static_cast<unsigned>(j)));
                EXPECT_EQ(W(row, model.standard_index("FC" + J)), own * config.options.coulomb(qd(static_cast<unsigned>(j))));
            }
        }
    }
    ::testing::Test::RecordProperty("worst_relative_difference", std::to_string(worst));
}

TEST(RneaVsKdl, Puma560MatchesKdlTo1e9) { compare_with_kdl("puma560.yaml"); }
TEST(RneaVsKdl, Ur5LikeMatchesKdlTo1e9) { compare_with_kdl("ur5_like.yaml"); }

}  // namespace
