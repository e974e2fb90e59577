// SPDX-License-Identifier: MIT
#pragma once
// A URDF rewritten with identified standard parameters (identify --export-urdf): every moving body's
// <inertial> and every moving joint's <dynamics damping friction>, everything else (visuals, collisions,
// limits, fixed links, comments, unknown elements) kept. The XML is edited with TinyXML, the library urdfdom
// reads URDF with, and the bodies are found by parse_urdf_chain, so they are exactly the ones whose standard
// parameters the model has:
//   - body j's standard parameters are about its frame, the child link of moving joint j (urdf_chain.hpp);
//     that link's <inertial> becomes mass M, origin xyz = (MX, MY, MZ) / M with rpy 0, and the inertia about
//     the centre of mass in the link frame, I_O - (|h|^2 1 - h h^T) / M (h the first moments);
//   - links fixed to a moving body were merged into its standard parameters: their <inertial> is removed
//     (a comment says where it went), otherwise it would be counted twice;
//   - <dynamics damping="FVj" friction="FCj"> on joint j (added when absent).
// Numbers are written with 17 significant digits: the file reads back to the same doubles' neighbours.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace jacobid::robot {

// One body's standard parameters XX XY XZ YY YZ ZZ MX MY MZ M about its frame origin, as URDF writes them.
struct CentralInertial {
    double mass = 0.0;
    Eigen::Vector3d com = Eigen::Vector3d::Zero();      // in the body frame
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about the centre of mass, body-frame axes
};
// A zero mass gives com 0 and the inertia as given (a massless body has no first moment to move it by).
CentralInertial central_inertial(const std::array<double, 10>& standard);

// Bodies whose central inertia no mass distribution has (principal moments breaking a + b >= c, a possible
// outcome of --semi-physical): one line each, naming the body by its joint. Simulators check this (MuJoCo
// refuses such a body), so the export says it rather than let a simulator fail later.
struct UrdfExport;
std::vector<std::string> impossible_inertias(const UrdfExport& values, const std::vector<std::string>& joint_names);

struct UrdfExport {
    std::vector<std::string> names;  // standard parameter names (XX1 ... M1, IA1, FV1, FC1, FOFF1, XX2, ...)
    Eigen::VectorXd values;          // same order
    std::string header;              // a comment put first inside <robot> (empty: none)
    std::vector<std::string> joint_notes;  // per moving joint, a comment before its <dynamics> (empty: none)
};

// `xml`: the URDF text; `source` names it in error messages. InputError for a URDF parse_urdf_chain refuses,
// or a standard parameter XXj..Mj missing from `values`.
std::string export_urdf(const std::string& xml, const std::string& source, const UrdfExport& values);

}  // namespace jacobid::robot
