// SPDX-License-Identifier: MIT
#include "payload/payload_inertia.hpp"

#include <fmt/core.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace jacobid::payload {
namespace {

Eigen::Matrix<double, 6, 1> packed(const Eigen::Matrix3d& m) {
    Eigen::Matrix<double, 6, 1> v;
    v << m(0, 0), m(0, 1), m(0, 2), m(1, 1), m(1, 2), m(2, 2);
    return v;
}

// m (|c|^2 E - c c^T): the inertia a point mass m at c adds about the origin (parallel axes).
Eigen::Matrix3d point_mass_inertia(double m, const Eigen::Vector3d& c) {
    return m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
}

}  // namespace

Eigen::Matrix3d inertia_matrix(const Eigen::Matrix<double, 6, 1>& i) {
    Eigen::Matrix3d m;
    m << i[0], i[1], i[2], i[1], i[3], i[4], i[2], i[4], i[5];
    return m;
}

Inertial10 flatten(const Inertial& i) {
    Inertial10 v;
    v[0] = i.mass;
    v.segment<3>(1) = i.com;
    v.tail<6>() = i.inertia;
    return v;
}

Inertial to_inertial(const Standard10& s, const Eigen::Isometry3d& tool) {
    Inertial out;
    out.mass = s[9];
    const Eigen::Vector3d c = s.segment<3>(6) / s[9];  // in the link frame
    const Eigen::Matrix3d about_com = inertia_matrix(s.head<6>()) - point_mass_inertia(s[9], c);
    const Eigen::Matrix3d r = tool.linear();
    out.com = r.transpose() * (c - tool.translation());
    out.inertia = packed(r.transpose() * about_com * r);
    return out;
}

Standard10 to_standard(const Inertial& i, const Eigen::Isometry3d& tool) {
    const Eigen::Matrix3d r = tool.linear();
    const Eigen::Vector3d c = tool.translation() + r * i.com;
    const Eigen::Matrix3d about_origin = r * inertia_matrix(i.inertia) * r.transpose() + point_mass_inertia(i.mass, c);
    // Segment by segment: a comma initializer of these sizes trips GCC 12's -Warray-bounds with AVX-512.
    Standard10 s;
    s.head<6>() = packed(about_origin);
    s.segment<3>(6) = i.mass * c;
    s[9] = i.mass;
    return s;
}

Eigen::Matrix<double, 10, 10> inertial_jacobian(const Standard10& s, const Eigen::Isometry3d& tool) {
    Eigen::Matrix<double, 10, 10> j;
    for (int k = 0; k < 10; ++k) {
        const double h = 1e-6 * std::max(1e-3, std::abs(s[k]));
        Standard10 up = s, down = s;
        up[k] += h;
        down[k] -= h;
        j.col(k) = (flatten(to_inertial(up, tool)) - flatten(to_inertial(down, tool))) / (2.0 * h);
    }
    return j;
}

std::vector<std::string> consistency_violations(const Inertial& i) {
    std::vector<std::string> out;
    if (!(i.mass > 0.0)) out.push_back(fmt::format("mass {:.4g} kg is not positive", i.mass));
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertia_matrix(i.inertia));
    const Eigen::Vector3d p = eig.eigenvalues();  // ascending
    if (!(p[0] > 0.0)) out.push_back(fmt::format("inertia about the centre of mass is not positive definite (principal moments {:.3g}, {:.3g}, {:.3g} kg.m^2)", p[0], p[1], p[2]));
    // With p ascending only the largest can exceed the sum of the others.
    if (p[2] > p[0] + p[1]) {
        out.push_back(fmt::format("triangle inequality fails: principal moment {:.3g} > {:.3g} + {:.3g} kg.m^2 (no mass distribution has it)", p[2], p[0], p[1]));
    }
    return out;
}

const std::vector<std::string>& standard_names() {
    static const std::vector<std::string> n = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"};
    return n;
}

const std::vector<std::string>& inertial_names() {
    static const std::vector<std::string> n = {"mass", "com_x", "com_y", "com_z", "I_xx", "I_xy", "I_xz", "I_yy", "I_yz", "I_zz"};
    return n;
}

}  // namespace jacobid::payload
