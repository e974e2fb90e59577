// SPDX-License-Identifier: MIT
// A robot description written back as YAML (robot_description.hpp to_yaml): what simulate puts in its truth
// file and --export-robot writes, read back by parse_robot_description bit for bit.
#include <yaml-cpp/yaml.h>

#include "robot/controller_description.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::robot {
namespace {

void emit_auto_or_per_joint(YAML::Emitter& out, bool is_auto, double common, const std::vector<double>& per_joint) {
    if (is_auto && per_joint.empty()) {
        out << "auto";
    } else if (!per_joint.empty()) {
        out << YAML::Flow << YAML::BeginSeq;
        for (const double a : per_joint) out << a;
        out << YAML::EndSeq;
    } else {
        out << common;
    }
}

}  // namespace

// Written with yaml-cpp's emitter, not by hand: names, column names and paths are free text (a ':' or a
// '#' in a joint name must be quoted to read back), and the emitter knows YAML's quoting rules.
std::string to_yaml(const RobotDescription& d) {
    YAML::Emitter out;
    out.SetDoublePrecision(17);  // every double reads back bit for bit
    out << YAML::BeginMap;
    out << YAML::Key << "model" << YAML::Value << d.model;
    if (d.model == "planar2r") out << YAML::Key << "L1" << YAML::Value << d.L1;
    if (d.model == "urdf") out << YAML::Key << "urdf" << YAML::Value << d.urdf;
    if (d.serial()) {
        out << YAML::Key << "gravity" << YAML::Value << YAML::Flow << YAML::BeginSeq << d.gravity.x() << d.gravity.y() << d.gravity.z()
            << YAML::EndSeq;
    }
    out << YAML::Key << "joints" << YAML::Value << YAML::BeginSeq;
    for (std::size_t k = 0; k < d.joints.size(); ++k) {
        const auto& j = d.joints[k];
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << j.name;
        if (d.model == "mdh") {
            const MdhJoint& m = d.mdh[k];
            out << YAML::Key << "sigma" << YAML::Value << (m.type == JointType::Prismatic ? 1 : 0);
            out << YAML::Key << "alpha" << YAML::Value << m.alpha << YAML::Key << "d" << YAML::Value << m.d;
            out << YAML::Key << "theta" << YAML::Value << m.theta << YAML::Key << "r" << YAML::Value << m.r;
            out << YAML::Key << "antecedent" << YAML::Value << m.antecedent + 1;
        }
        out << YAML::Key << "position" << YAML::Value << j.position_column << YAML::Key << "torque" << YAML::Value << j.torque_column;
        out << YAML::Key << "limits" << YAML::Value << YAML::Flow << YAML::BeginSeq << j.lower_limit << j.upper_limit << YAML::EndSeq;
        out << YAML::EndMap;
    }
    out << YAML::EndSeq;
    out << YAML::Key << "friction" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "coulomb" << YAML::Value << (d.coulomb.model == CoulombModel::Sign ? "sign" : "smooth");
    out << YAML::Key << "alpha" << YAML::Value;
    emit_auto_or_per_joint(out, d.coulomb_alpha_auto, d.coulomb.alpha, d.coulomb_alpha);
    out << YAML::Key << "offset" << YAML::Value << d.friction_offset;
    if (d.coulomb_load != CoulombLoad::none) out << YAML::Key << "coulomb_load" << YAML::Value << to_string(d.coulomb_load);
    if (d.presliding) {
        out << YAML::Key << "presliding" << YAML::Value << "dahl" << YAML::Key << "presliding_displacement" << YAML::Value;
        emit_auto_or_per_joint(out, d.presliding_displacement_auto, d.presliding_displacement, d.presliding_displacements);
        out << YAML::Key << "presliding_play" << YAML::Value << d.presliding_play;
    }
    out << YAML::EndMap;
    out << YAML::Key << "rotor_inertia" << YAML::Value << d.rotor_inertia;
    if (!d.parameters.empty()) {
        out << YAML::Key << "parameters" << YAML::Value << YAML::BeginMap;
        for (const auto& [name, value] : d.parameters) out << YAML::Key << name << YAML::Value << value;
        out << YAML::EndMap;
    }
    if (d.controller) write_controller(out, *d.controller);
    out << YAML::EndMap;
    return std::string(out.c_str()) + "\n";
}

}  // namespace jacobid::robot
