// SPDX-License-Identifier: MIT
// identify --export-urdf, the file itself (robot/urdf_export.hpp, identify/report/model_export.hpp): random
// physically consistent standard parameters of a test arm (rotated joint and inertial frames, a link fixed to
// the last body, a prismatic joint) written into its URDF, then
//   - that URDF read by urdfdom into a KDL tree without jacobid's urdf_chain (urdf_kdl_reference.hpp): KDL's
//     torques plus IA qdd + FV qd + FC c(qd) + FOFF equal the model's regressor times K s to 1e-9 (relative) on
//     random states;
//   - read again by jacobid: the same standard values (to rounding), so the same base values;
//   - everything but the identified inertials and <dynamics> unchanged (the XML trees compared);
//   - central_inertial against the closed form of an offset, rotated box.
#include <gtest/gtest.h>
#include <tinyxml.h>

#include <Eigen/Geometry>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

#include "identify/report/model_export.hpp"
#include "robot/robot_description.hpp"
#include "robot/serial_robot_model.hpp"
#include "robot/urdf_export.hpp"
#include "scratch_directory.hpp"
#include "urdf_kdl_reference.hpp"

namespace {

namespace fs = std::filesystem;
using namespace jacobid;

const std::string kArm = std::string(JACOBID_TESTS_DIR) + "/data/export_arm.urdf";

robot::RobotDescription arm_description(const std::string& urdf) {
    const fs::path dir = test::scratch_directory() / "urdf_export";
    fs::create_directories(dir);
    const std::string file = (dir / "arm.yaml").string();
    std::ofstream(file) << "model: urdf\nurdf: " << urdf
                        << "\ngravity: [0.3, -0.2, -9.81]\nfriction: {coulomb: smooth, alpha: [40, 80, 120, 160], offset: true}\nrotor_inertia: true\n";
    return robot::load_robot_description(file);
}

// A rigid body: mass m, centre of mass c, a box's central inertia (triangle inequalities hold) rotated by R.
Eigen::Matrix<double, 10, 1> random_body(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double m = 0.5 + 4.0 * u(rng);
    const Eigen::Vector3d c(0.2 * u(rng) - 0.1, 0.2 * u(rng) - 0.1, 0.2 * u(rng) - 0.1);
    const Eigen::Vector3d size(0.05 + 0.3 * u(rng), 0.05 + 0.3 * u(rng), 0.05 + 0.3 * u(rng));
    const Eigen::Vector3d s2 = size.cwiseProduct(size);
    const Eigen::Matrix3d central = (m / 12.0 * Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y())).asDiagonal();
    const Eigen::Matrix3d R = Eigen::Quaterniond(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized().toRotationMatrix();
    const Eigen::Matrix3d I = R * central * R.transpose() + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    Eigen::Matrix<double, 10, 1> p;
    p << I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2), m * c.x(), m * c.y(), m * c.z(), m;
    return p;
}

// Standard values in the model's order: random bodies, IA, FV, FC > 0 and an offset of either sign.
Eigen::VectorXd random_standard(const robot::SerialRobotModel& model, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Eigen::VectorXd s(model.standard_parameter_count());
    for (int j = 0; j < model.joint_count(); ++j) {
        const auto body = random_body(rng);
        static const char* kNames[10] = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"};
        for (int k = 0; k < 10; ++k) s[model.standard_index(std::string(kNames[k]) + std::to_string(j + 1))] = body[k];
        s[model.standard_index("IA" + std::to_string(j + 1))] = 0.01 + 0.1 * u(rng);
        s[model.standard_index("FV" + std::to_string(j + 1))] = 0.1 + u(rng);
        s[model.standard_index("FC" + std::to_string(j + 1))] = 0.1 + 2.0 * u(rng);
        s[model.standard_index("FOFF" + std::to_string(j + 1))] = u(rng) - 0.5;
    }
    return s;
}

struct Exported {
    robot::RobotDescription original;
    std::unique_ptr<robot::RobotModel> model;
    Eigen::VectorXd standard;
    std::string urdf;
};

Exported export_random(unsigned seed) {
    Exported e;
    e.original = arm_description(kArm);
    e.model = robot::make_robot_model(e.original);
    const auto& serial = dynamic_cast<const robot::SerialRobotModel&>(*e.model);
    std::mt19937 rng(seed);
    e.standard = random_standard(serial, rng);
    e.urdf = robot::export_urdf(test::read_text_file(kArm), kArm, {serial.standard_names(), e.standard, "a header", {"note 1 -- with dashes", "", "", ""}});
    return e;
}

double value(const robot::SerialRobotModel& model, const Eigen::VectorXd& s, const std::string& name) { return s[model.standard_index(name)]; }

TEST(UrdfExport, KdlTorquesFromTheExportedUrdfEqualTheIdentifiedModel) {
    const Exported e = export_random(11);
    const auto& serial = dynamic_cast<const robot::SerialRobotModel&>(*e.model);
    const Eigen::VectorXd x = serial.base_values(e.standard);  // the identified base parameters
    const test::UrdfKdlReference kdl(e.urdf);
    const int n = serial.joint_count();
    ASSERT_EQ(kdl.names, (std::vector<std::string>{"shoulder_pan", "shoulder_lift", "elbow", "slide"}));
    test::JointTerms terms;
    for (int j = 1; j <= n; ++j) {
        terms.ia.push_back(value(serial, e.standard, "IA" + std::to_string(j)));
        terms.foff.push_back(value(serial, e.standard, "FOFF" + std::to_string(j)));
        terms.coulomb.push_back({robot::CoulombModel::SmoothAtan, 40.0 * j});
    }
    const Eigen::Vector3d gravity(0.3, -0.2, -9.81);
    EXPECT_LT(test::worst_relative_difference(kdl, serial, x, gravity, terms, Eigen::Vector4d(2.5, 2.0, 3.0, 0.1)), 1e-9);
    // The test has teeth: the original URDF's inertials give other torques.
    const test::UrdfKdlReference original(test::read_text_file(kArm));
    EXPECT_GT(test::worst_relative_difference(original, serial, x, gravity, terms, Eigen::Vector4d(2.5, 2.0, 3.0, 0.1)), 1e-2);
}

TEST(UrdfExport, JacobidReadsBackTheSameStandardValues) {
    const Exported e = export_random(12);
    const auto& serial = dynamic_cast<const robot::SerialRobotModel&>(*e.model);
    const fs::path dir = test::scratch_directory() / "urdf_export";
    fs::create_directories(dir);
    const std::string urdf = (dir / "exported.urdf").string();
    std::ofstream(urdf) << e.urdf;
    // The description export (identify/report/model_export.hpp) pointing to it carries IA and FOFF.
    const std::vector<double> alphas{40, 80, 120, 160};
    const robot::RobotDescription written = identify::identified_description(e.original, serial.standard_names(), e.standard, alphas, "exported.urdf");
    const std::string yaml = (dir / "exported.yaml").string();
    std::ofstream(yaml) << robot::to_yaml(written);
    const robot::RobotDescription loaded = robot::load_robot_description(yaml);
    const auto model = robot::make_robot_model(loaded);
    const auto& reloaded = dynamic_cast<const robot::SerialRobotModel&>(*model);
    ASSERT_EQ(reloaded.standard_names(), serial.standard_names());
    const Eigen::VectorXd s = robot::standard_values(loaded, reloaded);
    for (int i = 0; i < s.size(); ++i) {
        EXPECT_NEAR(s[i], e.standard[i], 1e-13 * (1.0 + std::abs(e.standard[i]))) << serial.standard_names()[static_cast<std::size_t>(i)];
    }
    const Eigen::VectorXd x = serial.base_values(e.standard);
    EXPECT_LT((reloaded.base_values(s) - x).norm(), 1e-12 * x.norm());
    // Only what a URDF cannot carry is in `parameters`; the Coulomb smoothing is fixed.
    for (const auto& [name, v] : loaded.parameters) EXPECT_TRUE(name.rfind("IA", 0) == 0 || name.rfind("FOFF", 0) == 0) << name;
    EXPECT_EQ(loaded.parameters.size(), 8u);
    EXPECT_FALSE(loaded.coulomb_alpha_auto);
    EXPECT_EQ(loaded.coulomb_alpha, alphas);
}

// The document without comments, without the elements the export replaces.
std::string stripped(const std::string& xml) {
    TiXmlDocument doc;
    doc.Parse(xml.c_str());
    EXPECT_FALSE(doc.Error()) << doc.ErrorDesc();
    const std::set<std::string> bodies{"shoulder", "upper_arm", "forearm", "carriage", "tool"};
    const auto strip = [&](TiXmlNode& node, auto& self) -> void {
        for (TiXmlNode* child = node.FirstChild(); child;) {
            TiXmlNode* next = child->NextSibling();
            const TiXmlElement* element = child->ToElement();
            const TiXmlElement* parent = node.ToElement();
            const bool identified = element && parent && parent->Attribute("name") &&
                                    ((element->ValueStr() == "inertial" && bodies.count(parent->Attribute("name"))) ||
                                     (element->ValueStr() == "dynamics" && parent->ValueStr() == "joint"));
            if (child->ToComment() || identified) {
                node.RemoveChild(child);
            } else {
                self(*child, self);
            }
            child = next;
        }
    };
    strip(doc, strip);
    TiXmlPrinter printer;
    doc.Accept(&printer);
    return printer.Str();
}

TEST(UrdfExport, EverythingElseIsUnchanged) {
    const Exported e = export_random(13);
    const std::string original = test::read_text_file(kArm);
    EXPECT_EQ(stripped(e.urdf), stripped(original));
    EXPECT_NE(stripped(e.urdf).find("Gazebo/Grey"), std::string::npos);
    TiXmlDocument doc;
    doc.Parse(e.urdf.c_str());
    const TiXmlElement* robot = doc.FirstChildElement("robot");
    ASSERT_NE(robot, nullptr);
    std::map<std::string, const TiXmlElement*> links, joints;
    for (const TiXmlElement* l = robot->FirstChildElement("link"); l; l = l->NextSiblingElement("link")) links[l->Attribute("name")] = l;
    for (const TiXmlElement* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) joints[j->Attribute("name")] = j;
    for (const char* body : {"shoulder", "upper_arm", "forearm", "carriage"}) EXPECT_NE(links[body]->FirstChildElement("inertial"), nullptr) << body;
    EXPECT_EQ(links["tool"]->FirstChildElement("inertial"), nullptr) << "merged into carriage: it would count twice";
    EXPECT_NE(links["base"]->FirstChildElement("inertial"), nullptr) << "fixed to the base: not identified, kept";
    for (const char* joint : {"shoulder_pan", "shoulder_lift", "elbow", "slide"}) EXPECT_NE(joints[joint]->FirstChildElement("dynamics"), nullptr);
    EXPECT_EQ(joints["tool_mount"]->FirstChildElement("dynamics"), nullptr);
    EXPECT_NE(e.urdf.find("<!-- note 1 - - with dashes -->"), std::string::npos) << e.urdf;
    EXPECT_NE(e.urdf.find("<!-- a header -->"), std::string::npos);
}

TEST(UrdfExport, CentralInertialOfAnOffsetRotatedBox) {
    // A 2 kg box 0.3 x 0.2 x 0.1 m, rotated by 0.4 rad about z, centre at c: the standard values by the parallel axis theorem.
    const double m = 2.0;
    const Eigen::Vector3d c(0.1, -0.2, 0.3);
    const Eigen::Matrix3d central = (m / 12.0 * Eigen::Vector3d(0.04 + 0.01, 0.09 + 0.01, 0.09 + 0.04)).asDiagonal();
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Matrix3d Ig = R * central * R.transpose();
    const Eigen::Matrix3d I = Ig + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    const robot::CentralInertial body = robot::central_inertial({I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2), m * c.x(), m * c.y(), m * c.z(), m});
    EXPECT_DOUBLE_EQ(body.mass, 2.0);
    EXPECT_LT((body.com - c).norm(), 1e-15);
    EXPECT_LT((body.inertia - Ig).norm(), 1e-15);
}

}  // namespace

namespace {

TEST(UrdfExport, BodiesNoMassDistributionHasAreNamed) {
    // Central moments (0.01, 0.01, 0.05): 0.01 + 0.01 < 0.05, possible only under --semi-physical. A box
    // (0.02, 0.03, 0.04) is possible. Both offset from the frame origin, so the check must move them to the centre.
    const auto standard = [](const Eigen::Vector3d& central, int j) {
        const double m = 2.0;
        const Eigen::Vector3d c(0.1, 0.05, -0.2);
        const Eigen::Matrix3d I = Eigen::Matrix3d(central.asDiagonal()) + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
        const std::string n = std::to_string(j);
        return std::vector<std::pair<std::string, double>>{{"XX" + n, I(0, 0)}, {"XY" + n, I(0, 1)}, {"XZ" + n, I(0, 2)}, {"YY" + n, I(1, 1)},
                                                            {"YZ" + n, I(1, 2)}, {"ZZ" + n, I(2, 2)}, {"MX" + n, m * c.x()}, {"MY" + n, m * c.y()},
                                                            {"MZ" + n, m * c.z()}, {"M" + n, m}};
    };
    robot::UrdfExport e;
    e.values.resize(20);
    int k = 0;
    for (const auto& list : {standard({0.02, 0.03, 0.04}, 1), standard({0.01, 0.01, 0.05}, 2)}) {
        for (const auto& [name, v] : list) {
            e.names.push_back(name);
            e.values[k++] = v;
        }
    }
    const std::vector<std::string> lines = robot::impossible_inertias(e, {"a", "b"});
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("joint 2 ('b')"), std::string::npos) << lines[0];
    EXPECT_NE(lines[0].find("0.01, 0.01, 0.05"), std::string::npos) << lines[0];
}

}  // namespace
