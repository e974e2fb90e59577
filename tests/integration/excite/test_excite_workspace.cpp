// SPDX-License-Identifier: MIT
// jacobid excite --workspace-frame/--workspace-point/--workspace-box (issue 17), against independent
// references: the frames' forward kinematics against orocos-kdl's ChainFkSolverPos_recursive on every frame
// of three arms; the point's Jacobian against central differences of the kinematics; the box constraints'
// gradients against central differences of the constraint functions; a URDF link behind a fixed joint and
// a 2R trajectory against the planar closed form (x = l1 cos q1 + l2 cos(q1 + q2), ...); bad input.
#include <gtest/gtest.h>

#include <fmt/core.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "core/errors.hpp"
#include "excite/excitation_problem.hpp"
#include "excite/frame_kinematics.hpp"
#include "excite/workspace_box.hpp"
#include "io/csv_table.hpp"
#include "kdl_forward_kinematics.hpp"
#include "robot/robot_description.hpp"
#include "run_command.hpp"
#include "excite_test_support.hpp"
#include "scratch_directory.hpp"
#include "serial_test_support.hpp"

namespace {

namespace fs = std::filesystem;
using jacobid::test::run_command;
using namespace jacobid;

using test::kJacobid;
using test::kTwoLink;

std::string scratch(const std::string& name) { return test::excite_scratch("excite_workspace", name); }

// Random joint positions within [-2.5, 2.5] (prismatic joints within [-0.15, 0]).
std::vector<Eigen::VectorXd> random_poses(const robot::RobotDescription& robot, int count) {
    std::mt19937 rng(7);
    std::vector<Eigen::VectorXd> poses;
    for (int i = 0; i < count; ++i) {
        Eigen::VectorXd q(static_cast<Eigen::Index>(robot.chain.size()));
        for (std::size_t j = 0; j < robot.chain.size(); ++j) {
            const auto& jd = robot.joints[j];
            q[static_cast<Eigen::Index>(j)] = std::uniform_real_distribution<double>(jd.lower_limit, jd.upper_limit)(rng);
        }
        poses.push_back(q);
    }
    return poses;
}

// The chain's joints as plain arrays for the KDL reference.
std::vector<test::PlainJoint> plain(const std::vector<robot::ChainJoint>& chain) {
    std::vector<test::PlainJoint> out;
    for (const auto& j : chain) {
        test::PlainJoint p;
        p.revolute = j.type == robot::JointType::Revolute;
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) p.rotation[static_cast<std::size_t>(3 * r + c)] = j.rotation(r, c);
            p.position[static_cast<std::size_t>(r)] = j.position[r];
            p.axis[static_cast<std::size_t>(r)] = j.axis[r];
        }
        out.push_back(p);
    }
    return out;
}

TEST(FrameKinematics, EveryFrameMatchesKdlForwardKinematics) {
    for (const char* name : {"ur5_like.yaml", "puma560.yaml", "scara_rrpr.yaml"}) {
        const robot::RobotDescription robot = robot::load_robot_description(test::example_robot(name));
        const int n = static_cast<int>(robot.chain.size());
        const std::vector<test::PlainJoint> chain = plain(robot.chain);
        const Eigen::Vector3d point(0.03, -0.02, 0.05);
        for (const Eigen::VectorXd& q : random_poses(robot, 20)) {
            for (int j = 0; j < n; ++j) {
                const excite::FrameKinematics frame(robot.chain, j, {}, point);
                const std::array<double, 12> kdl = test::kdl_frame_pose(chain, std::vector<double>(q.data(), q.data() + n), j + 1);
                const Eigen::Matrix3d R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(kdl.data());
                const Eigen::Vector3d p(kdl[9], kdl[10], kdl[11]);
                const excite::FramePose pose = frame.frame(q);
                EXPECT_LT((pose.position - p).cwiseAbs().maxCoeff(), 1e-12) << name << " frame " << j + 1;
                EXPECT_LT((pose.rotation - R).cwiseAbs().maxCoeff(), 1e-12) << name << " frame " << j + 1;
                EXPECT_LT((frame.point(q, nullptr) - (p + R * point)).cwiseAbs().maxCoeff(), 1e-12) << name << " frame " << j + 1;
            }
        }
    }
}

TEST(FrameKinematics, PointJacobianMatchesCentralDifferences) {
    for (const char* name : {"ur5_like.yaml", "scara_rrpr.yaml"}) {  // revolute joints, and a prismatic one
        const robot::RobotDescription robot = robot::load_robot_description(test::example_robot(name));
        const int n = static_cast<int>(robot.chain.size());
        for (int j = 0; j < n; ++j) {
            const excite::FrameKinematics frame(robot.chain, j, {}, Eigen::Vector3d(0.1, 0.05, -0.07));
            for (const Eigen::VectorXd& q : random_poses(robot, 5)) {
                Eigen::Matrix3Xd J;
                frame.point(q, &J);
                ASSERT_EQ(J.cols(), n);
                const double h = 1e-6;
                for (int k = 0; k < n; ++k) {
                    Eigen::VectorXd qp = q, qm = q;
                    qp[k] += h, qm[k] -= h;
                    const Eigen::Vector3d fd = (frame.point(qp, nullptr) - frame.point(qm, nullptr)) / (2 * h);
                    EXPECT_LT((fd - J.col(k)).cwiseAbs().maxCoeff(), 1e-8) << name << " frame " << j + 1 << " joint " << k + 1;
                }
            }
        }
    }
}

TEST(WorkspaceBox, ConstraintGradientsMatchCentralDifferencesOfTheConstraints) {
    const robot::RobotDescription robot = robot::load_robot_description(test::example_robot("ur5_like.yaml"));
    const auto model = robot::make_robot_model(robot);
    const Eigen::VectorXd x = robot::true_parameters(robot, *model);
    std::vector<excite::JointLimits> limits(6);
    for (auto& l : limits) l.lower = -2.5, l.upper = 2.5, l.velocity = 3.0;
    const Eigen::VectorXd pose = Eigen::VectorXd::Constant(6, 0.3);
    // The tool flange's point 0.1 m along its z, in a box around where the pose puts it.
    const excite::FrameKinematics tool(robot.chain, 5, {}, Eigen::Vector3d(0, 0, 0.1));
    const Eigen::Vector3d start = tool.point(pose, nullptr);
    excite::Workspace w{tool, {start - Eigen::Vector3d(0.2, 0.3, 0.25), start + Eigen::Vector3d(0.35, 0.15, 0.3)}, start, "6"};
    excite::ProblemSettings settings;
    settings.samples = 40;
    excite::ExcitationProblem problem(*model, x, excite::FourierBasis(5.0, 2, 0.2), pose, limits, settings);
    const int before = problem.constraints();
    problem.set_workspace(w);
    ASSERT_EQ(problem.constraints(), before + excite::kBoxFaces);
    const Eigen::VectorXd c = 0.3 * Eigen::VectorXd::Random(problem.variables());
    Eigen::MatrixXd J;
    const Eigen::VectorXd g = problem.constraint_values(c, &J);
    // The aggregates bound the faces' terms from above: recompute the largest term from the sampled points.
    double worst = 0.0;
    for (int k = 0; k < problem.variables(); ++k) {
        const double h = 1e-6;
        Eigen::VectorXd cp = c, cm = c;
        cp[k] += h, cm[k] -= h;
        const Eigen::VectorXd fd = (problem.constraint_values(cp, nullptr) - problem.constraint_values(cm, nullptr)) / (2 * h);
        const auto rows = Eigen::seqN(problem.workspace_row(), excite::kBoxFaces);
        worst = std::max(worst, (fd(rows) - J.col(k)(rows)).cwiseAbs().maxCoeff() / std::max(1.0, fd(rows).cwiseAbs().maxCoeff()));
    }
    EXPECT_LT(worst, 1e-6);
    EXPECT_GT(J.middleRows(problem.workspace_row(), excite::kBoxFaces).cwiseAbs().maxCoeff(), 1e-3) << "the faces depend on the coefficients";
    // At rest (c = 0) the point stays at its start: every face at -1 (up to the aggregate's log(N) / rho).
    const Eigen::VectorXd rest = problem.constraint_values(Eigen::VectorXd::Zero(problem.variables()), nullptr);
    for (int f = 0; f < excite::kBoxFaces; ++f) EXPECT_NEAR(rest[problem.workspace_row() + f], -1.0 + std::log(40.0) / settings.ks_rho, 1e-12);
}

// The 2R of planar2r.urdf with a tool link behind a fixed joint: the URDF link frame against the closed form.
TEST(WorkspaceBox, UrdfLinkBehindAFixedJointMatchesThePlanarClosedForm) {
    std::ifstream in(std::string(JACOBID_SOURCE_DIR) + "/examples/robots/planar2r.urdf");
    std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    urdf.replace(urdf.find("</robot>"), 8,
                 "  <link name=\"tool0\"/>\n  <joint name=\"flange\" type=\"fixed\"><parent link=\"link2\"/><child link=\"tool0\"/>"
                 "<origin xyz=\"0.4 0 0\" rpy=\"0 0 0.3\"/></joint>\n</robot>\n");
    std::ofstream(scratch("tool.urdf")) << urdf;
    std::ofstream(scratch("tool.yaml")) << "model: urdf\nurdf: tool.urdf\n";
    const robot::RobotDescription robot = robot::load_robot_description(scratch("tool.yaml"));
    const std::vector<double> box = {-2, 2, -2, 2, -1, 1};
    for (const Eigen::Vector2d& q : {Eigen::Vector2d(0.3, -1.1), Eigen::Vector2d(-2.0, 2.4), Eigen::Vector2d(1.0, 0.5)}) {
        const excite::Workspace w = excite::make_workspace(robot, "tool0", {0.1, 0.02, 0.0}, box, q);
        const double q12 = q[0] + q[1], a = q12 + 0.3;
        const Eigen::Vector3d expected(0.5 * std::cos(q[0]) + 0.4 * std::cos(q12) + 0.1 * std::cos(a) - 0.02 * std::sin(a),
                                       0.5 * std::sin(q[0]) + 0.4 * std::sin(q12) + 0.1 * std::sin(a) + 0.02 * std::cos(a), 0.0);
        EXPECT_LT((w.start - expected).cwiseAbs().maxCoeff(), 1e-12) << q.transpose();
        // The child link of joint 2 is joint 2's frame, as the number 2 and `tool` name it.
        const Eigen::Vector3d elbow(0.5 * std::cos(q[0]) + 0.1 * std::cos(q12), 0.5 * std::sin(q[0]) + 0.1 * std::sin(q12), 0.0);
        for (const char* frame : {"link2", "2", "tool", "last"}) {
            EXPECT_LT((excite::make_workspace(robot, frame, {0.1, 0, 0}, box, q).start - elbow).cwiseAbs().maxCoeff(), 1e-12) << frame;
        }
    }
}

// The tip of the 2R (0.4 m along link 2) by the closed form.
Eigen::Vector2d tip(double q1, double q2) { return {0.5 * std::cos(q1) + 0.4 * std::cos(q1 + q2), 0.5 * std::sin(q1) + 0.4 * std::sin(q1 + q2)}; }

TEST(ExciteCli, TheWorkspaceBoxHoldsAtEveryRowAndChangesTheTrajectory) {
    // At the default pose (0, 0) the tip is at (0.9, 0); the box leaves it 0.3 m of x and +-0.25 m of y.
    // An evaluation budget, not a time limit: the boxed design had used its whole 10 s limit for a log det within 1 %
    // of what 120 evaluations reach in a fraction of a second, and depended on the machine's speed.
    const double xmin = 0.6, xmax = 0.95, ymin = -0.25, ymax = 0.25;
    const std::string common = " excite --quiet --robot " + kTwoLink + " --duration 10 --harmonics 3 --base-frequency 0.1 --velocity-limit 2 " +
                               "--acceleration-limit 8 --starts 1 --time-limit 600 --max-evaluations 120";
    const std::string boxed = scratch("boxed.csv"), boxed_json = scratch("boxed.json"), free = scratch("free.csv");
    const auto r = run_command(kJacobid + common + fmt::format(" --workspace-frame tool --workspace-point 0.4,0,0 --workspace-box {},{},{},{},-1,1", xmin,
                                                               xmax, ymin, ymax) +
                               " -o " + boxed + " --json " + boxed_json + " --plot " + scratch("boxed.png"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_EQ(run_command(kJacobid + common + " -o " + free).exit_code, 0);
    EXPECT_GT(fs::file_size(scratch("boxed.png")), 1000u);
    const io::CsvTable b = io::read_csv(boxed), f = io::read_csv(free);
    ASSERT_EQ(b.rows(), 10001u);
    Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
    bool free_leaves = false;
    double difference = 0.0;
    for (std::size_t i = 0; i < b.rows(); ++i) {
        const Eigen::Vector2d p = tip(b.column("q1")[i], b.column("q2")[i]);
        ASSERT_GE(p.x(), xmin) << "row " << i;
        ASSERT_LE(p.x(), xmax) << "row " << i;
        ASSERT_GE(p.y(), ymin) << "row " << i;
        ASSERT_LE(p.y(), ymax) << "row " << i;
        lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        const Eigen::Vector2d pf = tip(f.column("q1")[i], f.column("q2")[i]);
        free_leaves = free_leaves || pf.x() < xmin || pf.x() > xmax || pf.y() < ymin || pf.y() > ymax;
        difference = std::max({difference, std::abs(b.column("q1")[i] - f.column("q1")[i]), std::abs(b.column("q2")[i] - f.column("q2")[i])});
    }
    EXPECT_TRUE(free_leaves) << "without the box the tip must leave it, else the box does not bind";
    EXPECT_GT(difference, 0.1) << "the binding box must change the trajectory";
    // The box binds: some face is reached to within a few percent of its room.
    EXPECT_TRUE(hi.x() > xmax - 0.05 * (xmax - 0.9) || lo.x() < xmin + 0.05 * (0.9 - xmin) || hi.y() > 0.95 * ymax || lo.y() < 0.95 * ymin)
        << lo.transpose() << " " << hi.transpose();
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(boxed_json));
    const auto& w = j["workspace"];
    EXPECT_EQ(w["frame"], "tool");
    EXPECT_EQ(w["point"], (std::vector<double>{0.4, 0, 0}));
    EXPECT_EQ(w["box"], (std::vector<double>{xmin, xmax, ymin, ymax, -1, 1}));
    EXPECT_NEAR(w["start"][0].get<double>(), 0.9, 1e-12);
    EXPECT_NEAR(w["start"][1].get<double>(), 0.0, 1e-12);
    EXPECT_NEAR(w["min"][0].get<double>(), lo.x(), 1e-9);
    EXPECT_NEAR(w["max"][1].get<double>(), hi.y(), 1e-9);
    const double margin = std::min({xmax - hi.x(), lo.x() - xmin, ymax - hi.y(), lo.y() - ymin, 1.0});
    EXPECT_NEAR(w["margin"].get<double>(), margin, 1e-9);
}

TEST(ExciteCli, AFaceCrossedBetweenTheOptimizersSamplesIsTightenedUntilEveryRowIsInside) {
    // 10 samples per period for 3 harmonics: the optimizer misses the point's peaks between its samples, the
    // control-rate check finds them and the tightening rounds move the faces in. (With 6, below 2 x 3 + 1, the
    // samples alias the third harmonic and whether 4 rounds suffice depended on the compiler: now refused.)
    const std::string csv = scratch("sparse.csv"), json = scratch("sparse.json");
    const auto r = run_command(kJacobid + " excite --quiet --criterion cond --robot " + kTwoLink + " --duration 10 --harmonics 3 --base-frequency 0.1 --starts 1 " +
                               "--time-limit 10 --samples 10 --workspace-frame tool --workspace-point 0.4,0,0 --workspace-box 0.6,0.95,-0.25,0.25,-1,1 -o " +
                               csv + " --json " + json);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_GE(nlohmann::json::parse(std::ifstream(json))["tightening_rounds"].get<int>(), 1);
    const io::CsvTable t = io::read_csv(csv);
    for (std::size_t i = 0; i < t.rows(); ++i) {
        const Eigen::Vector2d p = tip(t.column("q1")[i], t.column("q2")[i]);
        ASSERT_TRUE(p.x() >= 0.6 && p.x() <= 0.95 && p.y() >= -0.25 && p.y() <= 0.25) << "row " << i << ": " << p.transpose();
    }
}

TEST(ExciteCli, BadWorkspaceInputIsOneLineNamingTheOption) {
    std::ofstream(scratch("urdf2r.yaml")) << "model: urdf\nurdf: " << JACOBID_SOURCE_DIR << "/examples/robots/planar2r.urdf\n";
    struct Case {
        std::string robot, args, expected;
    };
    const std::string box = " --workspace-box 0,1,-1,1,-1,1";
    const std::vector<Case> cases = {
        {kTwoLink, "--workspace-frame 2", "--workspace-frame: needs --workspace-box"},
        {kTwoLink, box, "--workspace-box: needs --workspace-frame"},
        {kTwoLink, "--workspace-point 1,0,0", "--workspace-point: needs --workspace-frame"},
        {kTwoLink, "--workspace-frame 3" + box, "--workspace-frame 3: expected a joint number 1 .. 2, tool or last"},
        {kTwoLink, "--workspace-frame 0" + box, "--workspace-frame 0: expected a joint number 1 .. 2"},
        {kTwoLink, "--workspace-frame link2" + box, "--workspace-frame link2: expected a joint number 1 .. 2, tool or last (link names need a URDF robot)"},
        {scratch("urdf2r.yaml"), "--workspace-frame nosuch" + box, "--workspace-frame nosuch: no such link in"},
        {scratch("urdf2r.yaml"), "--workspace-frame base" + box, "--workspace-frame base: the link is fixed to the base"},
        {kTwoLink, "--workspace-frame 2 --workspace-box 0,1,-1,1", "--workspace-box: 4 values (expected xmin,xmax,ymin,ymax,zmin,zmax"},
        {kTwoLink, "--workspace-frame 2 --workspace-box 0,1,1,-1,-1,1", "--workspace-box: ymin 1 >= ymax -1 (expected min < max)"},
        {kTwoLink, "--workspace-frame 2 --workspace-box 0,inf,-1,1,-1,1", "--workspace-box: value 2 is inf (expected a finite number, m)"},
        {kTwoLink, "--workspace-frame 2 --workspace-point 1,0" + box, "--workspace-point: 2 values (expected x,y,z"},
        {kTwoLink, "--harmonics 3 --samples 6", "--samples 6: expected 0 (automatic) or at least 2 x --harmonics + 1 = 7 samples per period"},
        {kTwoLink, "--workspace-frame 2 --workspace-point 0.4,0,0 --workspace-box 1,2,-1,1,-1,1",
         "--workspace-box: at the start pose the point of frame 2 is at x = 0.9 m, not strictly inside [1, 2]"},
        {std::string(JACOBID_SOURCE_DIR) + "/examples/robots/planar2r.yaml", "--workspace-frame 2" + box, "--workspace-frame: needs a serial robot"},
    };
    for (const auto& c : cases) {
        const auto r = run_command(kJacobid + " excite --quiet --robot " + c.robot + " -o " + scratch("bad.csv") + " " + c.args);
        EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
        EXPECT_NE(r.err.find("jacobid excite: error: " + c.expected), std::string::npos) << c.args << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << ": " << r.err;
    }
}

}  // namespace
