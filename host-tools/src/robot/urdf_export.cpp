// SPDX-License-Identifier: MIT
#include "robot/urdf_export.hpp"

#include <fmt/core.h>
#include <tinyxml.h>

#include <Eigen/Eigenvalues>

#include <map>

#include "core/errors.hpp"
#include "robot/urdf_chain.hpp"

namespace jacobid::robot {
namespace {

std::string number(double v) { return fmt::format("{:.17g}", v); }

std::string triple(const Eigen::Vector3d& v) { return fmt::format("{} {} {}", number(v.x()), number(v.y()), number(v.z())); }

// XML comments may not contain "--" (nor end with '-').
TiXmlComment comment(std::string text) {
    for (std::size_t at = text.find("--"); at != std::string::npos; at = text.find("--")) text.replace(at, 2, "- -");
    TiXmlComment c;
    c.SetValue(" " + text + " ");
    return c;
}

// The <robot>'s direct children named `tag` (link or joint) by their name attribute.
std::map<std::string, TiXmlElement*> children_by_name(TiXmlElement& robot, const char* tag) {
    std::map<std::string, TiXmlElement*> found;
    for (TiXmlElement* e = robot.FirstChildElement(tag); e; e = e->NextSiblingElement(tag)) {
        if (const char* name = e->Attribute("name")) found[name] = e;
    }
    return found;
}

TiXmlElement inertial_element(const CentralInertial& body) {
    TiXmlElement inertial("inertial");
    TiXmlElement origin("origin");
    origin.SetAttribute("xyz", triple(body.com));
    origin.SetAttribute("rpy", "0 0 0");
    inertial.InsertEndChild(origin);
    TiXmlElement mass("mass");
    mass.SetAttribute("value", number(body.mass));
    inertial.InsertEndChild(mass);
    TiXmlElement inertia("inertia");
    const Eigen::Matrix3d& I = body.inertia;
    inertia.SetAttribute("ixx", number(I(0, 0)));
    inertia.SetAttribute("ixy", number(I(0, 1)));
    inertia.SetAttribute("ixz", number(I(0, 2)));
    inertia.SetAttribute("iyy", number(I(1, 1)));
    inertia.SetAttribute("iyz", number(I(1, 2)));
    inertia.SetAttribute("izz", number(I(2, 2)));
    inertial.InsertEndChild(inertia);
    return inertial;
}

// Replaces the link's <inertial> in place (or adds one first), keeping the element order of the file.
void set_inertial(TiXmlElement& link, const CentralInertial& body) {
    const TiXmlElement replacement = inertial_element(body);
    if (TiXmlElement* old = link.FirstChildElement("inertial")) {
        link.ReplaceChild(old, replacement);
    } else if (TiXmlNode* first = link.FirstChild()) {
        link.InsertBeforeChild(first, replacement);
    } else {
        link.InsertEndChild(replacement);
    }
}

void set_dynamics(TiXmlElement& joint, double damping, double friction, const std::string& note) {
    TiXmlElement* dynamics = joint.FirstChildElement("dynamics");
    if (!dynamics) dynamics = joint.InsertEndChild(TiXmlElement("dynamics"))->ToElement();
    dynamics->SetAttribute("damping", number(damping));
    dynamics->SetAttribute("friction", number(friction));
    if (!note.empty()) joint.InsertBeforeChild(dynamics, comment(note));
}

class Values {
public:
    Values(const UrdfExport& e, std::string source) : source_(std::move(source)) {
        for (std::size_t i = 0; i < e.names.size() && static_cast<Eigen::Index>(i) < e.values.size(); ++i) {
            values_[e.names[i]] = e.values[static_cast<Eigen::Index>(i)];
        }
    }
    bool has(const std::string& name) const { return values_.count(name) > 0; }
    double at(const std::string& name) const {
        const auto it = values_.find(name);
        if (it == values_.end()) throw InputError(fmt::format("{}: no value for standard parameter '{}' to export", source_, name));
        return it->second;
    }
    std::array<double, 10> body(std::size_t j) const {
        static const char* kNames[10] = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"};
        std::array<double, 10> p{};
        for (std::size_t k = 0; k < p.size(); ++k) p[k] = at(fmt::format("{}{}", kNames[k], j + 1));
        return p;
    }

private:
    std::string source_;
    std::map<std::string, double> values_;
};

}  // namespace

CentralInertial central_inertial(const std::array<double, 10>& p) {
    CentralInertial body;
    body.mass = p[9];
    const Eigen::Vector3d h(p[6], p[7], p[8]);
    body.inertia << p[0], p[1], p[2], p[1], p[3], p[4], p[2], p[4], p[5];
    if (body.mass == 0.0) return body;
    body.com = h / body.mass;
    body.inertia -= (h.squaredNorm() * Eigen::Matrix3d::Identity() - h * h.transpose()) / body.mass;
    return body;
}

std::vector<std::string> impossible_inertias(const UrdfExport& e, const std::vector<std::string>& joint_names) {
    const Values values(e, "export");
    std::vector<std::string> lines;
    for (std::size_t j = 0; j < joint_names.size(); ++j) {
        const Eigen::Vector3d m = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(central_inertial(values.body(j)).inertia).eigenvalues();  // ascending
        if (m[0] >= 0.0 && m[0] + m[1] >= m[2] * (1.0 - 1e-9)) continue;
        lines.push_back(fmt::format("the body of joint {} ('{}') has principal moments {:.6g}, {:.6g}, {:.6g} kg.m^2 about its centre of mass: no "
                                    "mass distribution has them ({}); simulators may refuse it (MuJoCo does)",
                                    j + 1, joint_names[j], m[0], m[1], m[2], m[0] < 0.0 ? "a negative moment" : "the two smaller sum to less than the largest"));
    }
    return lines;
}

std::string export_urdf(const std::string& xml, const std::string& source, const UrdfExport& e) {
    const UrdfChain chain = parse_urdf_chain(xml, source);  // the bodies exactly as the model has them
    TiXmlDocument doc;
    doc.Parse(xml.c_str(), nullptr, TIXML_ENCODING_UTF8);
    TiXmlElement* robot = doc.Error() ? nullptr : doc.FirstChildElement("robot");
    if (!robot) throw InputError(fmt::format("{}: cannot re-read the URDF as XML: {}", source, doc.Error() ? doc.ErrorDesc() : "no <robot>"));
    const auto links = children_by_name(*robot, "link");
    const auto joints = children_by_name(*robot, "joint");
    const Values values(e, source);
    if (!e.header.empty()) {
        if (TiXmlNode* first = robot->FirstChild()) {
            robot->InsertBeforeChild(first, comment(e.header));
        } else {
            robot->InsertEndChild(comment(e.header));
        }
    }
    for (std::size_t j = 0; j < chain.joints.size(); ++j) {
        const std::string& body_link = chain.body_links[j];
        set_inertial(*links.at(body_link), central_inertial(values.body(j)));
        for (const std::string& merged : chain.merged_links[j]) {
            TiXmlElement& link = *links.at(merged);
            TiXmlElement* old = link.FirstChildElement("inertial");
            link.InsertBeforeChild(old, comment(fmt::format("jacobid: this link's inertial is part of the identified inertial of link '{}' "
                                                            "(one rigid body with it)", body_link)));
            link.RemoveChild(old);
        }
        const std::string fv = fmt::format("FV{}", j + 1), fc = fmt::format("FC{}", j + 1);
        const std::string note = j < e.joint_notes.size() ? e.joint_notes[j] : std::string();
        if (values.has(fv) && values.has(fc)) set_dynamics(*joints.at(chain.names[j]), values.at(fv), values.at(fc), note);
    }
    TiXmlPrinter printer;
    printer.SetIndent("  ");
    doc.Accept(&printer);
    return printer.Str();
}

}  // namespace jacobid::robot
