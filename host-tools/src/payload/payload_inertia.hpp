// SPDX-License-Identifier: MIT
#pragma once
// A payload's inertial description two ways (docs/method.md, "Payload identification"; docs/identify.md,
// "Payload"):
//   - the ten standard parameters about the last link's frame origin, in its axes, XX XY XZ YY YZ ZZ MX MY MZ M
//     (what the regressor sees: they add to the last link's own, identify/drive_gains/drive_gains.hpp);
//   - mass, centre of mass and inertia about the centre of mass, in a tool frame fixed to the last link (what a
//     controller's payload setting asks for).
// Conversions between them, their Jacobian (for the delta-method std) and the physical-consistency checks.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace jacobid::payload {

using Standard10 = Eigen::Matrix<double, 10, 1>;

// Mass (kg), centre of mass (m) and inertia about it (XX XY XZ YY YZ ZZ, kg.m^2), in one frame.
struct Inertial {
    double mass = 0.0;
    Eigen::Vector3d com = Eigen::Vector3d::Zero();
    Eigen::Matrix<double, 6, 1> inertia = Eigen::Matrix<double, 6, 1>::Zero();
};
using Inertial10 = Eigen::Matrix<double, 10, 1>;  // m, cx, cy, cz, IXX IXY IXZ IYY IYZ IZZ (about the CoM)
Inertial10 flatten(const Inertial& i);

// `tool`: the tool frame's pose in the last link's frame (identity: the link frame itself).
Inertial to_inertial(const Standard10& standard, const Eigen::Isometry3d& tool);
Standard10 to_standard(const Inertial& inertial, const Eigen::Isometry3d& tool);
// d flatten(to_inertial(s)) / d s (central differences: the map is a rational function, smooth where m != 0).
Eigen::Matrix<double, 10, 10> inertial_jacobian(const Standard10& standard, const Eigen::Isometry3d& tool);

Eigen::Matrix3d inertia_matrix(const Eigen::Matrix<double, 6, 1>& i);

// Physical consistency of a rigid body: mass > 0, inertia about the centre of mass positive definite, each
// principal moment at most the sum of the other two (triangle inequalities). Empty: consistent; else one
// sentence per failed check.
std::vector<std::string> consistency_violations(const Inertial& inertial);

// The parameter names, "XX" .. "M" and "mass", "com_x" .. "I_zz".
const std::vector<std::string>& standard_names();
const std::vector<std::string>& inertial_names();

}  // namespace jacobid::payload
