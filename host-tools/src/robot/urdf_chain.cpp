// SPDX-License-Identifier: MIT
#include "robot/urdf_chain.hpp"

#include <console_bridge/console.h>
#include <fmt/core.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

#include "core/errors.hpp"
#include "jacobid/yaml/input_file.hpp"

namespace jacobid::robot {
namespace {

struct Transform {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    Transform then(const Transform& next) const { return {R * next.R, p + R * next.p}; }
};

Transform to_transform(const urdf::Pose& pose) {
    double x = 0, y = 0, z = 0, w = 1;
    pose.rotation.getQuaternion(x, y, z, w);
    Transform t;
    t.R = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
    t.p = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
    return t;
}

// Inertial parameters of one body about a frame origin: XX XY XZ YY YZ ZZ MX MY MZ M.
using Inertial10 = std::array<double, 10>;

// The link's inertial expressed in the frame `to_link` maps from (link frame -> body frame).
Inertial10 inertial_in(const urdf::Inertial& in, const Transform& body_to_link) {
    const Transform inertial = body_to_link.then(to_transform(in.origin));
    Eigen::Matrix3d Ig;
    Ig << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    const Eigen::Vector3d c = inertial.p;
    const Eigen::Matrix3d I = inertial.R * Ig * inertial.R.transpose() + in.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    const Eigen::Vector3d ms = in.mass * c;
    return {I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2), ms.x(), ms.y(), ms.z(), in.mass};
}

class Converter {
public:
    Converter(std::string source) : source_(std::move(source)) {}

    UrdfChain convert(const urdf::ModelInterface& model) {
        const auto root = model.getRoot();
        if (!root) throw InputError(fmt::format("{}: the URDF has no root link", source_));
        visit(*root, -1, Transform{});
        // After the walk, so that a cycle (which makes the walk itself wrong) is the error reported first.
        if (bad_limit_) throw InputError(*bad_limit_);
        if (chain_.joints.empty()) throw InputError(fmt::format("{}: element <robot name='{}'>: no revolute, continuous or prismatic joint", source_, model.getName()));
        static const char* kNames[10] = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"};
        for (std::size_t j = 0; j < inertials_.size(); ++j) {
            for (int k = 0; k < 10; ++k) chain_.standard_parameters.emplace_back(fmt::format("{}{}", kNames[k], j + 1), inertials_[j][static_cast<std::size_t>(k)]);
            // Friction only where the URDF gives <dynamics>: an absent value is unknown, not a prior of 0.
            if (!has_dynamics_[j]) continue;
            chain_.standard_parameters.emplace_back(fmt::format("FV{}", j + 1), damping_[j]);
            chain_.standard_parameters.emplace_back(fmt::format("FC{}", j + 1), friction_[j]);
        }
        return std::move(chain_);
    }

private:
    std::string element(const urdf::Joint& joint) const { return fmt::format("{}: element <joint name='{}'>", source_, joint.name); }

    // urdfdom reads a <limit> without lower/upper as 0, 0: such a joint, or one with lower >= upper, used to be
    // given [-pi, pi] silently (issue 36), and excite designed motions over it.
    std::string limit_error(const urdf::Joint& joint) const {
        const bool prismatic = joint.type == urdf::Joint::PRISMATIC;
        const std::string limit = joint.limits ? fmt::format("<limit lower='{:g}' upper='{:g}'>", joint.limits->lower, joint.limits->upper) : "no <limit>";
        return fmt::format("{}: {}: a {} joint needs <limit lower upper> with lower < upper ({}){}", element(joint), limit,
                           prismatic ? "prismatic" : "revolute", prismatic ? "m" : "rad",
                           prismatic ? "" : "; a joint that turns without limits is type='continuous' (its range is then taken as [-pi, pi])");
    }

    void add_inertial(int body, const urdf::Link& link, const Transform& body_to_link) {
        if (body < 0 || !link.inertial) return;  // the base (or a link fixed to it) does not move
        const Inertial10 p = inertial_in(*link.inertial, body_to_link);
        for (double v : p) {
            if (!std::isfinite(v)) throw InputError(fmt::format("{}: element <link name='{}'>: <inertial> must be finite numbers", source_, link.name));
        }
        for (std::size_t k = 0; k < p.size(); ++k) inertials_[static_cast<std::size_t>(body)][k] += p[k];
        if (link.name != chain_.body_links[static_cast<std::size_t>(body)]) chain_.merged_links[static_cast<std::size_t>(body)].push_back(link.name);
    }

    // `link` belongs to the moving body `body` (-1: base); `body_to_link` maps link coordinates to body coordinates.
    void visit(const urdf::Link& link, int body, const Transform& body_to_link) {
        visited_.insert(&link);
        chain_.links.push_back({link.name, body, body_to_link.R, body_to_link.p});
        add_inertial(body, link, body_to_link);
        for (const auto& joint_ptr : link.child_joints) {
            const urdf::Joint& joint = *joint_ptr;
            const auto child = link.child_links.empty() ? nullptr : find_child(link, joint.child_link_name);
            if (!child) throw InputError(fmt::format("{}: child link '{}' not found", element(joint), joint.child_link_name));
            // urdfdom accepts a joint whose child is its own parent or an ancestor: following it would recurse
            // forever (a stack overflow found by fuzz_urdf). A kinematic tree visits every link once.
            if (visited_.count(child)) {
                throw InputError(fmt::format("{}: child link '{}' is already in the tree (the URDF has a cycle)", element(joint), joint.child_link_name));
            }
            const Transform origin = body_to_link.then(to_transform(joint.parent_to_joint_origin_transform));
            if (joint.type == urdf::Joint::FIXED) {
                visit(*child, body, origin);
                continue;
            }
            if (joint.type != urdf::Joint::REVOLUTE && joint.type != urdf::Joint::CONTINUOUS && joint.type != urdf::Joint::PRISMATIC) {
                throw InputError(fmt::format("{}: joint type is not supported (expected revolute, continuous, prismatic or fixed)", element(joint)));
            }
            if (joint.mimic) throw InputError(fmt::format("{}: mimic joints are not supported", element(joint)));
            ChainJoint c;
            c.type = joint.type == urdf::Joint::PRISMATIC ? JointType::Prismatic : JointType::Revolute;
            c.antecedent = body;
            c.rotation = origin.R;
            c.position = origin.p;
            c.axis = Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z);
            if (!c.rotation.allFinite() || !c.position.allFinite() || !c.axis.allFinite()) {
                throw InputError(fmt::format("{}: <origin> and <axis> must be finite numbers", element(joint)));
            }
            if (!(c.axis.norm() > 1e-9)) throw InputError(fmt::format("{}: <axis xyz> must not be zero", element(joint)));
            c.axis.normalize();
            // A continuous joint has no limits: its range is taken as one turn, [-pi, pi] (what excite designs
            // within; logged positions are not checked against it). Any other joint's <limit> is its range.
            double lower = -M_PI, upper = M_PI;
            bool given = false;
            if (joint.type != urdf::Joint::CONTINUOUS) {
                if (!joint.limits || !(joint.limits->upper > joint.limits->lower)) {
                    if (!bad_limit_) bad_limit_ = limit_error(joint);
                } else {
                    lower = joint.limits->lower;
                    upper = joint.limits->upper;
                    given = true;
                }
            }
            const int index = static_cast<int>(chain_.joints.size());
            chain_.joints.push_back(c);
            chain_.names.push_back(joint.name);
            chain_.limits.emplace_back(lower, upper);
            chain_.limits_given.push_back(given);
            chain_.body_links.push_back(child->name);
            chain_.merged_links.emplace_back();
            inertials_.push_back({});
            if (joint.dynamics && (!std::isfinite(joint.dynamics->damping) || !std::isfinite(joint.dynamics->friction))) {
                throw InputError(fmt::format("{}: <dynamics damping friction> must be finite numbers", element(joint)));
            }
            has_dynamics_.push_back(joint.dynamics != nullptr);
            damping_.push_back(joint.dynamics ? joint.dynamics->damping : 0.0);
            friction_.push_back(joint.dynamics ? joint.dynamics->friction : 0.0);
            visit(*child, index, Transform{});
        }
    }

    static const urdf::Link* find_child(const urdf::Link& link, const std::string& name) {
        for (const auto& child : link.child_links) {
            if (child && child->name == name) return child.get();
        }
        return nullptr;
    }

    std::string source_;
    std::set<const urdf::Link*> visited_;
    UrdfChain chain_;
    std::vector<Inertial10> inertials_;
    std::vector<double> damping_, friction_;
    std::vector<bool> has_dynamics_;
    std::optional<std::string> bad_limit_;  // the first joint whose limits are not a range
};

// Every number of a URDF <inertial> (mass, origin, inertia) read as a finite double: urdfdom stops at the
// first one it cannot read ("nan"), prints its own message and keeps the link with what it had read so far
// (e.g. a mass without its inertia), so such a link would be simulated and identified wrongly.
bool finite_numbers(const char* text) {
    std::istringstream in(text);
    std::string token;
    while (in >> token) {
        char* end = nullptr;
        const double v = std::strtod(token.c_str(), &end);
        if (end != token.c_str() + token.size() || !std::isfinite(v)) return false;
    }
    return true;
}

void require_finite_inertials(const std::string& xml, const std::string& source) {
    TiXmlDocument doc;
    doc.Parse(xml.c_str());
    const TiXmlElement* robot = doc.FirstChildElement("robot");
    for (const TiXmlElement* link = robot ? robot->FirstChildElement("link") : nullptr; link; link = link->NextSiblingElement("link")) {
        const TiXmlElement* inertial = link->FirstChildElement("inertial");
        for (const TiXmlElement* e = inertial ? inertial->FirstChildElement() : nullptr; e; e = e->NextSiblingElement()) {
            for (const TiXmlAttribute* a = e->FirstAttribute(); a; a = a->Next()) {
                if (finite_numbers(a->Value())) continue;
                throw InputError(fmt::format("{}: element <link name='{}'>: <inertial> <{} {}='{}'>: expected finite numbers", source,
                                             link->Attribute("name") ? link->Attribute("name") : "", e->Value(), a->Name(), a->Value()));
            }
        }
    }
}

// While it lives, urdfdom's errors (console_bridge) are caught instead of printed: the first is the cause of
// a refused URDF ("Failed to build tree: child link [lx] of joint [j2] not found"), which our message then
// names instead of a list of possible causes (issue 36); warnings and the rest pass on to the handler it replaced.
class UrdfdomErrors : public console_bridge::OutputHandler {
public:
    UrdfdomErrors() : lock_(mutex()), previous_(console_bridge::getOutputHandler()) { console_bridge::useOutputHandler(this); }
    ~UrdfdomErrors() override { console_bridge::useOutputHandler(previous_); }
    UrdfdomErrors(const UrdfdomErrors&) = delete;
    UrdfdomErrors& operator=(const UrdfdomErrors&) = delete;

    void log(const std::string& text, console_bridge::LogLevel level, const char* filename, int line) override {
        if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
            if (first_.empty()) first_ = text;  // the later ones follow from it; the URDF is refused
        } else if (previous_) {
            previous_->log(text, level, filename, line);
        }
    }
    const std::string& first() const { return first_; }

private:
    // console_bridge's handler is process-wide: one parse at a time swaps it.
    static std::mutex& mutex() {
        static std::mutex m;
        return m;
    }
    std::lock_guard<std::mutex> lock_;
    console_bridge::OutputHandler* previous_;
    std::string first_;
};

}  // namespace

UrdfChain parse_urdf_chain(const std::string& xml, const std::string& source) {
    require_finite_inertials(xml, source);
    urdf::ModelInterfaceSharedPtr model;
    std::string urdfdom_error;
    try {
        UrdfdomErrors errors;
        model = urdf::parseURDF(xml);
        urdfdom_error = errors.first();
    } catch (const std::exception& e) {
        throw InputError(fmt::format("{}: invalid URDF: {}", source, e.what()));
    }
    // Also when urdfdom returned a model: it logs an error where it skipped what it could not read (an
    // <inertial> it dropped), and the robot would then not be the one the file describes.
    if (!urdfdom_error.empty()) throw InputError(fmt::format("{}: invalid URDF: {} (urdfdom)", source, urdfdom_error));
    if (!model) {
        throw InputError(fmt::format("{}: invalid URDF (urdfdom rejected it without saying why: malformed XML, a missing <robot>, a joint without "
                                     "parent/child, a link named twice or a number that does not parse)",
                                     source));
    }
    return Converter(source).convert(*model);
}

UrdfChain load_urdf_chain(const std::string& path) {
    return parse_urdf_chain(yaml::read_input_file<InputError>(path, "URDF"), path);
}

}  // namespace jacobid::robot
