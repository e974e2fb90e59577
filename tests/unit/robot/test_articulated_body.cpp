// SPDX-License-Identifier: MIT
// The articulated-body forward dynamics (lib/include/jacobid/robot/articulated_body.hpp) against two
// independent references, on the PUMA 560, the UR5-like arm, the SCARA (prismatic quill) and the 6-joint
// URDF test arm (4 moving joints), at random states:
//  - the inertia-matrix route of the host model (M(q) by n + 2 Newton-Euler evaluations, Cholesky solve of
//    M qdd = tau - h), on the base parameters the simulator integrates, friction and rotor inertia included:
//    equal to 1e-10 relative;
//  - orocos-kdl (Debian): ChainFdSolver_RNE (which forms its own inertia matrix) gives the same qdd, and
//    ChainIdSolver_RNE turns our qdd back into the torques, both to 1e-9 relative.
// And: a call allocates nothing; a non-positive-definite inertia is reported, not integrated.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "allocation_counter.hpp"
#include "jacobid/robot/articulated_body.hpp"
#include "kdl_links.hpp"
#include "serial_test_support.hpp"

namespace {

using namespace jacobid;

robot::RobotDescription load(const std::string& robot) {
    if (robot == "export_arm.urdf") {
        // The URDF test arm through a description (its inertials are the parameters); the path resolves
        // against the description's own directory.
        return robot::parse_robot_description("model: urdf\nurdf: export_arm.urdf\n", std::string(JACOBID_TESTS_DIR) + "/data/arm.yaml");
    }
    return robot::load_robot_description(test::example_robot(robot));
}

std::string scientific(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2e", value);
    return text;
}

const char* const kRobots[] = {"puma560.yaml", "ur5_like.yaml", "scara_rrpr.yaml", "export_arm.urdf"};

double relative_difference(const double* a, const double* b, int n) {
    double scale = 1.0, worst = 0.0;
    for (int j = 0; j < n; ++j) scale = std::max(scale, std::abs(b[j]));
    for (int j = 0; j < n; ++j) worst = std::max(worst, std::abs(a[j] - b[j]) / scale);
    return worst;
}

TEST(ArticulatedBody, EqualsInertiaMatrixRouteTo1e10) {
    for (const char* robot : kRobots) {
        const auto d = load(robot);
        const auto model = robot::make_robot_model(d);
        const int n = model->joint_count();
        const Eigen::VectorXd x = robot::true_parameters(d, *model);
        robot::ForwardDynamics aba(*model, x);
        robot::ForwardDynamics reference(*model, x, robot::ForwardDynamicsSolver::inertia_matrix);
        ASSERT_EQ(aba.solver(), robot::ForwardDynamicsSolver::articulated_body) << robot;
        ASSERT_EQ(reference.solver(), robot::ForwardDynamicsSolver::inertia_matrix) << robot;
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        double worst = 0.0;
        for (int trial = 0; trial < 300; ++trial) {
            double q[robot::kMaxSerialJoints], qd[robot::kMaxSerialJoints], tau[robot::kMaxSerialJoints];
            double a[robot::kMaxSerialJoints], b[robot::kMaxSerialJoints];
            for (int j = 0; j < n; ++j) q[j] = 3.0 * u(rng), qd[j] = 2.0 * u(rng), tau[j] = 30.0 * u(rng);
            ASSERT_TRUE(aba.accelerations(q, qd, tau, a)) << robot;
            ASSERT_TRUE(reference.accelerations(q, qd, tau, b)) << robot;
            const double diff = relative_difference(a, b, n);
            worst = std::max(worst, diff);
            ASSERT_LT(diff, 1e-10) << robot << " trial " << trial;
            // And back through the model's inverse dynamics.
            double back[robot::kMaxSerialJoints];
            aba.torques(q, qd, a, back);
            ASSERT_LT(relative_difference(back, tau, n), 1e-10) << robot << " trial " << trial;
        }
        ::testing::Test::RecordProperty(std::string("worst_relative_difference_") + robot, scientific(worst));
    }
}

// The lib model of a description's chain and standard parameters, and the same robot for KDL.
template <int N>
struct BothModels {
    explicit BothModels(const robot::RobotDescription& d)
        : config(test::serial_config(d)), host(config), body(chain(config), config.gravity) {
        const Eigen::VectorXd standard = robot::standard_values(d, host);
        const robot::StandardParameterLayout<N> layout(N, config.options);
        body.set_standard_parameters(layout, standard);
        kdl = std::make_unique<test::KdlDynamics>(test::kdl_links(config, standard), test::kdl_gravity(config));
    }
    static robot::KinematicChain<N> chain(const robot::SerialRobotConfig& config) {
        robot::KinematicChain<N> c;
        for (const auto& joint : config.joints) EXPECT_EQ(c.add(joint), robot::ChainError::Ok);
        return c;
    }
    robot::SerialRobotConfig config;
    robot::SerialRobotModel host;
    robot::ArticulatedBody<N> body;
    std::unique_ptr<test::KdlDynamics> kdl;
};

template <int N>
void compare_with_kdl(const char* robot) {
    const auto d = load(robot);
    ASSERT_EQ(static_cast<int>(d.chain.size()), N) << robot;
    BothModels<N> models(d);
    typename robot::ArticulatedBody<N>::Data data;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    double worst_fd = 0.0, worst_id = 0.0;
    bool rotor_inertia = false;
    for (int j = 0; j < N; ++j) rotor_inertia = rotor_inertia || models.body.link(j).rotor_inertia > 0.0;
    for (int trial = 0; trial < 300; ++trial) {
        robot::JointVector<N> q, qd, tau, qdd;
        for (int j = 0; j < N; ++j) q[j] = 3.0 * u(rng), qd[j] = 2.0 * u(rng), tau[j] = 30.0 * u(rng);
        ASSERT_EQ(models.body.forward_dynamics(q, qd, tau, data, qdd), robot::ArticulatedBodyStatus::Ok) << robot;
        double kdl_qdd[N], kdl_tau[N];
        ASSERT_TRUE(models.kdl->forward_dynamics(q.data(), qd.data(), tau.data(), kdl_qdd)) << robot;
        ASSERT_TRUE(models.kdl->inverse_dynamics(q.data(), qd.data(), qdd.data(), kdl_tau)) << robot;
        const double fd = relative_difference(qdd.data(), kdl_qdd, N), id = relative_difference(kdl_tau, tau.data(), N);
        worst_fd = std::max(worst_fd, fd), worst_id = std::max(worst_id, id);
        ASSERT_LT(fd, 1e-9) << robot << " trial " << trial;
        ASSERT_LT(id, 1e-9) << robot << " trial " << trial;
    }
    ::testing::Test::RecordProperty(std::string("worst_fd_") + robot, scientific(worst_fd));
    ::testing::Test::RecordProperty(std::string("worst_id_") + robot, scientific(worst_id));
    if (std::string(robot) == "puma560.yaml") {
        EXPECT_TRUE(rotor_inertia) << "the PUMA's rotor inertias must be part of the comparison";
    }
}

TEST(ArticulatedBody, Puma560MatchesKdlFdAndIdTo1e9) { compare_with_kdl<6>("puma560.yaml"); }
TEST(ArticulatedBody, Ur5LikeMatchesKdlFdAndIdTo1e9) { compare_with_kdl<6>("ur5_like.yaml"); }
TEST(ArticulatedBody, ScaraWithPrismaticJointMatchesKdlFdAndIdTo1e9) { compare_with_kdl<4>("scara_rrpr.yaml"); }
TEST(ArticulatedBody, UrdfArmMatchesKdlFdAndIdTo1e9) { compare_with_kdl<4>("export_arm.urdf"); }

TEST(ArticulatedBody, AllocatesNothingPerCall) {
    const auto d = load("puma560.yaml");
    const auto model = robot::make_robot_model(d);
    robot::ForwardDynamics dynamics(*model, robot::true_parameters(d, *model));
    BothModels<6> models(d);
    typename robot::ArticulatedBody<6>::Data data;
    double q[6] = {0.1, -0.4, 0.8, 0.2, -0.5, 0.3}, qd[6] = {0.5, -0.2, 0.1, 1.0, -1.5, 2.0}, tau[6] = {5, 40, 10, 1, 0.5, 0.2}, qdd[6];
    robot::JointVector<6> vq = Eigen::Map<robot::JointVector<6>>(q), vqd = Eigen::Map<robot::JointVector<6>>(qd),
                          vtau = Eigen::Map<robot::JointVector<6>>(tau), vqdd;
    const std::uint64_t before = test::allocation_count();
    double sum = 0.0;
    for (int call = 0; call < 10000; ++call) {
        q[0] = 1e-4 * call;
        ASSERT_TRUE(dynamics.accelerations(q, qd, tau, qdd));
        vq[0] = q[0];
        ASSERT_EQ(models.body.forward_dynamics(vq, vqd, vtau, data, vqdd), robot::ArticulatedBodyStatus::Ok);
        sum += qdd[0] + vqdd[0];
    }
    EXPECT_EQ(test::allocation_count() - before, 0u);
    EXPECT_TRUE(std::isfinite(sum));
}

// Parameters no rigid body can have (every inertial value negated: M(q) negative definite) are refused by
// both routes alike, and a non-finite input is refused before any arithmetic.
TEST(ArticulatedBody, RefusesWhatTheInertiaMatrixRouteRefuses) {
    const auto d = load("ur5_like.yaml");
    const auto model = robot::make_robot_model(d);
    const Eigen::VectorXd x = -robot::true_parameters(d, *model);
    robot::ForwardDynamics aba(*model, x), reference(*model, x, robot::ForwardDynamicsSolver::inertia_matrix);
    const double q[6] = {0.3, -0.7, 1.1, 0.2, 0.4, -0.9}, zero[6] = {}, tau[6] = {1, 2, 3, 4, 5, 6};
    double qdd[6] = {7, 7, 7, 7, 7, 7};
    EXPECT_FALSE(reference.accelerations(q, zero, tau, qdd));
    EXPECT_FALSE(aba.accelerations(q, zero, tau, qdd));
    EXPECT_EQ(qdd[0], 7.0);  // untouched

    BothModels<6> models(d);
    typename robot::ArticulatedBody<6>::Data data;
    robot::JointVector<6> vq = robot::JointVector<6>::Zero(), vqd = vq, vtau = vq, vqdd = vq;
    vqd[2] = std::nan("");
    EXPECT_EQ(models.body.forward_dynamics(vq, vqd, vtau, data, vqdd), robot::ArticulatedBodyStatus::NonFiniteInput);
}

}  // namespace
