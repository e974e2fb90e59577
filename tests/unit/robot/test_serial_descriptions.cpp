// SPDX-License-Identifier: MIT
// Robot descriptions of serial robots: MDH tables and URDF files load into the same chain (a URDF written
// for the same robot gives the same torques as its MDH table), and malformed input is rejected with a
// one-line error naming the file and line (YAML) or the element (URDF).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "core/errors.hpp"
#include "robot/urdf_chain.hpp"
#include "serial_test_support.hpp"

namespace {

using namespace jacobid;

std::string error_of(const std::string& yaml) { return test::description_error_of(yaml); }

std::string urdf_error_of(const std::string& xml) {
    try {
        robot::parse_urdf_chain(xml, "arm.urdf");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(MdhDescription, MalformedTablesNameFileLineAndField) {
    EXPECT_EQ(error_of("model: mdh\n"), "r.yaml:1:1: joints: missing (required): model mdh needs one MDH row per joint (sigma, alpha, d, theta, r)");
    EXPECT_EQ(error_of("model: mdh\njoints:\n  - {name: a, alpha: 0}\n"), "r.yaml:3:5: joints[0].sigma: missing (required): 0 revolute, 1 prismatic");
    EXPECT_EQ(error_of("model: mdh\njoints:\n  - {sigma: 2}\n"), "r.yaml:3:13: joints[0].sigma: must be 0 (revolute) or 1 (prismatic), got 2");
    EXPECT_EQ(error_of("model: mdh\njoints:\n  - {sigma: 0, d: abc}\n"), "r.yaml:3:19: joints[0].d: expected a number, got 'abc'");
    EXPECT_EQ(error_of("model: mdh\njoints:\n  - {sigma: 0, length: 1}\n"),
              "r.yaml:3:16: joints[0].length: unknown key (known: alpha, antecedent, d, limits, name, position, r, sigma, theta, torque)");
    EXPECT_EQ(error_of("model: mdh\njoints:\n  - {sigma: 0}\n  - {sigma: 0, antecedent: 2}\n"),
              "r.yaml:4:28: joints[1].antecedent: must be 0 (base) to 1 (an earlier joint), got 2");
    EXPECT_EQ(error_of("model: mdh\njoints:\n  - {sigma: 1}\n"), "r.yaml:3:5: joints[0].limits: required for a prismatic joint: [lower, upper] in m");
    EXPECT_EQ(error_of("model: mdh\ngravity: [0, 0]\njoints:\n  - {sigma: 0}\n"), "r.yaml:2:10: gravity: must be a list of 3 numbers [gx, gy, gz] in m/s^2");
    EXPECT_EQ(error_of("model: planar2r\ngravity: [0, 0, -9.81]\n"), "r.yaml:2:10: gravity: is only for model mdh or urdf");
    const std::string unknown = error_of("model: mdh\njoints:\n  - {sigma: 0}\nparameters:\n  ZZ1R: 1.0\n");
    EXPECT_EQ(unknown.rfind("r.yaml:5:3: unknown parameter 'ZZ1R' (this model has: XX1, XY1, XZ1, YY1", 0), 0u) << unknown;
    EXPECT_EQ(error_of("model: urdf\n"), "r.yaml:1:1: urdf: missing (required): model urdf needs 'urdf: <file.urdf>' (relative to this file)");
    EXPECT_EQ(error_of("model: scara\n"), "r.yaml:1:8: model: 'scara' is not one of: planar2r, mdh, urdf");
}

// Fuzzer findings (fuzz/findings, docs/reliability.md): a list used as a key, and numbers so large that the
// regressor overflows, are input errors naming the file, not crashes.
TEST(MdhDescription, ListAsKeyIsAnInputError) {
    EXPECT_EQ(error_of("model: planar2r\n[a, b]: 1\n"), "r.yaml:2:1: (top level): expected a key name, found a list or map used as a key");
}

TEST(MdhDescription, OverflowingGeometryIsRejectedByTheModel) {
    const auto d = robot::parse_robot_description("model: mdh\njoints:\n  - {sigma: 0}\n  - {sigma: 0, d: 1e200}\n", "r.yaml");
    try {
        robot::make_robot_model(d);
        ADD_FAILURE() << "a 1e200 m link was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("r.yaml: the regressor is not finite", 0), 0u) << e.what();
    }
}

// Found by fuzz_robot_description (10-minute run): "r: 175707963, ..., r: 0.3" in one joint. yaml-cpp keeps
// both and a lookup returns the first, so the 1.8e8 m offset was used, and beside 0.3 m links the
// base-parameter QR could not decide the rank: an uncaught std::runtime_error (terminate).
TEST(MdhDescription, RepeatedKeyIsAnInputError) {
    EXPECT_EQ(error_of("model: mdh\njoints:\n  - {sigma: 0, r: 175707963, d: 0.3, r: 0.3}\n"), "r.yaml:3:38: joints[0].r: appears twice");
    EXPECT_EQ(error_of("model: planar2r\nL1: 0.5\nL1: 0.6\n"), "r.yaml:3:1: L1: appears twice");
}

TEST(MdhDescription, GeometryTooBadlyScaledForTheBaseParametersIsAnInputError) {
    const auto d = robot::parse_robot_description(
        "model: mdh\njoints:\n  - {sigma: 0}\n  - {sigma: 0, alpha: 10, r: 175707963, d: 0.3}\n"
        "  - {sigma: 1, alpha: 4, d: 0.4, theta: 5, antecedent: 2, limits: [0, 0.2]}\n",
        "r.yaml");
    // Either a model (another machine's rounding may decide the rank) or a one-line InputError; any other
    // exception fails the test (gtest reports it), which is what crashed the fuzzer.
    try {
        robot::make_robot_model(d);
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("r.yaml: base parameters: ", 0), 0u) << e.what();
        EXPECT_NE(std::string(e.what()).find("check the lengths"), std::string::npos) << e.what();
    }
}

// A 2-link arm: joint 1 about z at the base, joint 2 about y at 0.3 m up and 0.1 m out, a fixed tool
// link on link 2 (merged into link 2's inertia).
const char* kArm = R"(<robot name="arm">
  <link name="base"/>
  <link name="l1"><inertial><origin xyz="0.05 0.01 0.1" rpy="0 0 0"/><mass value="3"/>
    <inertia ixx="0.02" ixy="0.001" ixz="0" iyy="0.03" iyz="0.002" izz="0.01"/></inertial></link>
  <link name="l2"><inertial><origin xyz="0.2 0 0.02" rpy="0.3 0.1 -0.2"/><mass value="2"/>
    <inertia ixx="0.004" ixy="0" ixz="0.0005" iyy="0.05" iyz="0" izz="0.05"/></inertial></link>
  <link name="tool"><inertial><origin xyz="0 0 0" rpy="0 0 0"/><mass value="0.5"/>
    <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0" rpy="0 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="10" velocity="1"/><dynamics damping="0.3" friction="0.7"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/><origin xyz="0.1 0 0.3" rpy="0 0 0"/>
    <axis xyz="0 1 0"/></joint>
  <joint name="flange" type="fixed"><parent link="l2"/><child link="tool"/><origin xyz="0.4 0 0" rpy="0 0 0"/></joint>
</robot>)";

TEST(UrdfChain, SameTorquesAsTheEquivalentMdhTable) {
    const robot::UrdfChain urdf = robot::parse_urdf_chain(kArm, "arm.urdf");
    ASSERT_EQ(urdf.joints.size(), 2u);
    EXPECT_EQ(urdf.names, (std::vector<std::string>{"j1", "j2"}));
    EXPECT_DOUBLE_EQ(urdf.limits[1].first, -M_PI);
    robot::SerialRobotConfig from_urdf;
    from_urdf.name = "urdf";
    from_urdf.joints = urdf.joints;
    const robot::SerialRobotModel model(from_urdf);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(model.standard_parameter_count());
    for (const auto& [name, value] : urdf.standard_parameters) x[model.standard_index(name)] = value;
    EXPECT_DOUBLE_EQ(x[model.standard_index("M2")], 2.5);  // l2 + the fixed tool
    EXPECT_DOUBLE_EQ(x[model.standard_index("FV1")], 0.3);
    EXPECT_DOUBLE_EQ(x[model.standard_index("FC1")], 0.7);
    EXPECT_NEAR(x[model.standard_index("MX2")], 2.0 * 0.2 + 0.5 * 0.4, 1e-15);

    // Independent check by energy: with gravity off and qd = 0, tau = M(q) qdd, and qdd^T M qdd / 2 is the
    // kinetic energy at velocity qdd, computed here directly from the URDF's bodies (centre-of-mass velocity
    // and angular velocity of each body).
    robot::SerialRobotConfig no_gravity = from_urdf;
    no_gravity.gravity.setZero();
    const robot::SerialRobotModel inertia_only(no_gravity);
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::MatrixXd W(2, inertia_only.standard_parameter_count());
    for (int trial = 0; trial < 20; ++trial) {
        const double q[2] = {2 * u(rng), 2 * u(rng)}, zero[2] = {0, 0}, v[2] = {u(rng), u(rng)};
        inertia_only.standard_regressor(q, zero, v, W);
        const double twice_energy_model = Eigen::Vector2d(v[0], v[1]).dot(W * x);
        // Bodies in the base frame.
        const Eigen::Matrix3d R1 = Eigen::AngleAxisd(q[0], Eigen::Vector3d::UnitZ()).toRotationMatrix();
        const Eigen::Vector3d o2 = R1 * Eigen::Vector3d(0.1, 0, 0.3);
        const Eigen::Matrix3d R2 = R1 * Eigen::AngleAxisd(q[1], Eigen::Vector3d::UnitY()).toRotationMatrix();
        const Eigen::Vector3d w1 = v[0] * Eigen::Vector3d::UnitZ(), w2 = w1 + v[1] * (R1 * Eigen::Vector3d::UnitY());
        const auto body = [&](double m, const Eigen::Matrix3d& R, const Eigen::Vector3d& origin, const Eigen::Vector3d& c_local,
                              const Eigen::Matrix3d& Ic_local, const Eigen::Vector3d& w, const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& axes) {
            const Eigen::Vector3d c = origin + R * c_local;
            Eigen::Vector3d vc = Eigen::Vector3d::Zero();
            for (const auto& [point, omega] : axes) vc += omega.cross(c - point);
            return m * vc.squaredNorm() + w.dot(R * Ic_local * R.transpose() * w);
        };
        Eigen::Matrix3d I1, I2, It;
        I1 << 0.02, 0.001, 0, 0.001, 0.03, 0.002, 0, 0.002, 0.01;
        const Eigen::Matrix3d Rrpy = (Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()) *
                                      Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())).toRotationMatrix();
        I2 << 0.004, 0, 0.0005, 0, 0.05, 0, 0.0005, 0, 0.05;
        It = 0.001 * Eigen::Matrix3d::Identity();
        const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> axes1 = {{Eigen::Vector3d::Zero(), w1}};
        const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> axes2 = {{Eigen::Vector3d::Zero(), w1}, {o2, v[1] * (R1 * Eigen::Vector3d::UnitY())}};
        const double twice_energy = body(3.0, R1, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.05, 0.01, 0.1), I1, w1, axes1) +
                                    body(2.0, R2, o2, Eigen::Vector3d(0.2, 0, 0.02), Rrpy * I2 * Rrpy.transpose(), w2, axes2) +
                                    body(0.5, R2, o2, Eigen::Vector3d(0.4, 0, 0), It, w2, axes2);
        EXPECT_NEAR(twice_energy_model, twice_energy, 1e-12);
    }
}

TEST(UrdfDescription, Planar2RFromUrdfHasThePaperBaseSetAndValues) {
    // examples/robots/planar2r_urdf.yaml -> planar2r.urdf (path relative to the YAML), through make_robot_model
    // and true_parameters like `jacobid simulate` does.
    const auto d = robot::load_robot_description(test::example_robot("planar2r_urdf.yaml"));
    EXPECT_EQ(d.model, "urdf");
    EXPECT_EQ(d.joints[0].name, "j1");
    EXPECT_EQ(d.joints[1].torque_column, "tau2");
    const auto model = robot::make_robot_model(d);
    const std::vector<std::string> paper = {"ZZ1R", "FV1", "FC1", "ZZ2", "MX2", "MY2", "FV2", "FC2"};
    ASSERT_EQ(model->parameter_names(), paper);
    const Eigen::VectorXd x = robot::true_parameters(d, *model);
    const double table2[8] = {3.496, 0.248, 0.431, 0.059, 0.124, 0.0019, 0.0144, 0.1268};
    for (int c = 0; c < 8; ++c) EXPECT_NEAR(x[c], table2[c], 1e-12) << paper[static_cast<std::size_t>(c)];
    // The description round-trips (the truth file of `jacobid simulate` stores to_yaml()).
    const auto again = robot::parse_robot_description(robot::to_yaml(d), test::example_robot("planar2r_urdf.yaml"));
    EXPECT_EQ(again.chain.size(), 2u);
    EXPECT_EQ(robot::true_parameters(again, *robot::make_robot_model(again)), x);
}

TEST(MdhDescription, RoundTripsThroughToYaml) {
    const auto d = robot::load_robot_description(test::example_robot("scara_rrpr.yaml"));
    const auto again = robot::parse_robot_description(robot::to_yaml(d), "again.yaml");
    ASSERT_EQ(again.mdh.size(), 4u);
    EXPECT_EQ(again.mdh[2].type, robot::JointType::Prismatic);
    EXPECT_EQ(again.joints[2].lower_limit, -0.15);
    const auto model = robot::make_robot_model(d);
    EXPECT_EQ(robot::true_parameters(again, *robot::make_robot_model(again)), robot::true_parameters(d, *model));
}

// Found by fuzz_robot_description: to_yaml wrote names unquoted, so a joint or column name that YAML
// reads as syntax (': ', ',', '#', '{', a leading '- ' or quote) did not read back.
TEST(MdhDescription, NamesThatLookLikeYamlSyntaxRoundTrip) {
    const std::string text = R"(model: mdh
joints:
  - {name: "a: b", sigma: 0, alpha: 0, d: 0, theta: 0, r: 0, position: "q1, raw", torque: "#tau1"}
  - {name: "{x}", sigma: 0, alpha: 1.5707963267948966, d: 0.1, theta: 0, r: 0, position: "- q2", torque: "'t2"}
parameters:
  ZZ1: 0.25
)";
    const auto d = robot::parse_robot_description(text, "names.yaml");
    ASSERT_EQ(d.joints.size(), 2u);
    const auto again = robot::parse_robot_description(robot::to_yaml(d), "again.yaml");
    ASSERT_EQ(again.joints.size(), 2u);
    for (std::size_t j = 0; j < 2; ++j) {
        EXPECT_EQ(again.joints[j].name, d.joints[j].name);
        EXPECT_EQ(again.joints[j].position_column, d.joints[j].position_column);
        EXPECT_EQ(again.joints[j].torque_column, d.joints[j].torque_column);
    }
    EXPECT_EQ(again.joints[0].name, "a: b");
    EXPECT_EQ(again.joints[1].torque_column, "'t2");
    EXPECT_EQ(again.mdh[1].alpha, d.mdh[1].alpha);
    EXPECT_EQ(again.parameters, d.parameters);
}

// Found by fuzz_urdf (10-minute run): urdfdom accepted this file, whose joint j2 has l1 as parent and
// child; following the tree recursed until the stack overflowed.
TEST(UrdfChain, LinkThatIsItsOwnChildIsAnErrorNotAStackOverflow) {
    const char* cyclic = R"URDF(<robot name="arm">
  <link name="base"/>
  <link name="l1"><inertial><origin  izz="0.001"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="1 0 0" rpy="0 0 0"/>
    <cali xyz="3 5 1"/><limit loer="2" effort="10" velocity="1"/><dynamncs damping="0.3" friction="0.7"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l1"/><origin xyfloatz="027777777777777777777777777777777777777777777777777779777777777771 0 0.3" rpy="0 0 0"/>
x a   <is xyz="0 1 0"/>></joint>
</robot>
)URDF";
    // Since issue 36 an error urdfdom logs is the refusal, here before the walk: l1's <inertial> (no mass),
    // which urdfdom dropped while accepting the file.
    EXPECT_EQ(urdf_error_of(cyclic), "arm.urdf: invalid URDF: Inertial element must have a mass element (urdfdom)");
    // The walk itself still stops at a cycle in a file urdfdom reads without an error.
    const char* clean_cycle = R"URDF(<robot name="arm">
  <link name="base"/>
  <link name="l1"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l1"/><axis xyz="0 1 0"/></joint>
</robot>
)URDF";
    EXPECT_EQ(urdf_error_of(clean_cycle), "arm.urdf: element <joint name='j2'>: child link 'l1' is already in the tree (the URDF has a cycle)");
}

TEST(UrdfChain, MalformedUrdfNamesTheElement) {
    std::string floating = kArm;
    floating.replace(floating.find("type=\"continuous\""), 17, "type=\"floating\"");
    EXPECT_EQ(urdf_error_of(floating),
              "arm.urdf: element <joint name='j2'>: joint type is not supported (expected revolute, continuous, prismatic or fixed)");
    std::string zero_axis = kArm;
    zero_axis.replace(zero_axis.find("<axis xyz=\"0 1 0\"/>"), 19, "<axis xyz=\"0 0 0\"/>");
    EXPECT_EQ(urdf_error_of(zero_axis), "arm.urdf: element <joint name='j2'>: <axis xyz> must not be zero");
    std::string infinite = kArm;
    infinite.replace(infinite.find("xyz=\"0.1 0 0.3\""), 15, "xyz=\"inf 0 0.3\"");
    EXPECT_EQ(urdf_error_of(infinite).rfind("arm.urdf: ", 0), 0u);  // urdfdom itself rejects it, or our finiteness check
    std::string missing_child = kArm;
    missing_child.replace(missing_child.find("<child link=\"l2\"/>"), 18, "<child link=\"lx\"/>");
    // urdfdom's own reason (issue 36: was a list of possible causes, its "Error:" line printed apart).
    EXPECT_EQ(urdf_error_of(missing_child), "arm.urdf: invalid URDF: Failed to build tree: child link [lx] of joint [j2] not found (urdfdom)");
    EXPECT_EQ(urdf_error_of("<robot name='r'><link name='a'/><link name='a'/></robot>"), "arm.urdf: invalid URDF: link 'a' is not unique. (urdfdom)");
    EXPECT_EQ(urdf_error_of("<robot name='r'><link name='a'/></robot>"), "arm.urdf: element <robot name='r'>: no revolute, continuous or prismatic joint");
    EXPECT_EQ(urdf_error_of("not xml").rfind("arm.urdf: invalid URDF", 0), 0u);
}

// Issue 36: a revolute joint whose <limit> is not a range (lower >= upper, or no lower/upper, which urdfdom
// reads as 0, 0) was given [-pi, pi] silently, and excite designed motions over it. A continuous joint keeps
// [-pi, pi] (kArm's j2).
TEST(UrdfChain, LimitsThatAreNotARangeAreRefusedNamingTheJoint) {
    const std::string limit = "<limit lower=\"-2\" upper=\"2\" effort=\"10\" velocity=\"1\"/>";
    const auto with_limit = [&](const std::string& replacement) {
        std::string xml = kArm;
        return xml.replace(xml.find(limit), limit.size(), replacement);
    };
    const std::string continuous = "; a joint that turns without limits is type='continuous' (its range is then taken as [-pi, pi])";
    EXPECT_EQ(urdf_error_of(with_limit("<limit lower=\"1\" upper=\"1\" effort=\"10\" velocity=\"1\"/>")),
              "arm.urdf: element <joint name='j1'>: <limit lower='1' upper='1'>: a revolute joint needs <limit lower upper> with lower < upper (rad)" +
                  continuous);
    EXPECT_EQ(urdf_error_of(with_limit("<limit lower=\"2\" upper=\"-2\" effort=\"10\" velocity=\"1\"/>")),
              "arm.urdf: element <joint name='j1'>: <limit lower='2' upper='-2'>: a revolute joint needs <limit lower upper> with lower < upper (rad)" +
                  continuous);
    EXPECT_EQ(urdf_error_of(with_limit("<limit effort=\"10\" velocity=\"1\"/>")),
              "arm.urdf: element <joint name='j1'>: <limit lower='0' upper='0'>: a revolute joint needs <limit lower upper> with lower < upper (rad)" +
                  continuous);
    const robot::UrdfChain fine = robot::parse_urdf_chain(kArm, "arm.urdf");
    EXPECT_EQ(fine.limits[0], std::make_pair(-2.0, 2.0));
    EXPECT_TRUE(fine.limits_given[0]);
    EXPECT_EQ(fine.limits[1], std::make_pair(-M_PI, M_PI));  // continuous
    EXPECT_FALSE(fine.limits_given[1]);
}

}  // namespace
