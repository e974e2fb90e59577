// SPDX-License-Identifier: MIT
#pragma once
// orocos-kdl's dynamics solvers (ChainIdSolver_RNE, ChainFdSolver_RNE) behind an interface of plain
// doubles, as the independent reference of the articulated-body tests and the multibody benchmark.
//
// Why a separate library with no Eigen type in its interface: Debian builds KDL for the default x86-64
// (16-byte Eigen alignment), our targets are built with -march=native (32 or 64 bytes). KDL's solver
// objects hold Eigen members, so constructing or destroying them in a -march=native translation unit
// lays them out differently from the KDL code that uses them (ChainFdSolver_RNE crashed in its
// destructor). This library is compiled without -march, and only doubles cross its boundary.
#include <array>
#include <memory>
#include <vector>

namespace jacobid::test {

// One joint and the link it moves, in the terms of robot::ChainJoint and the standard parameters.
struct KdlLink {
    bool prismatic = false;
    std::array<double, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major: joint frame in the antecedent frame at q = 0
    std::array<double, 3> position{};                           // joint frame origin in the antecedent frame
    std::array<double, 3> axis{0, 0, 1};                        // unit, in the joint frame
    std::array<double, 10> inertial{};  // XX XY XZ YY YZ ZZ MX MY MZ M about the link origin, in the link frame
    double rotor_inertia = 0.0;         // KDL's joint inertia: tau_j += IA qdd_j
};

class KdlDynamics {
public:
    // A serial chain (each link's antecedent is the previous one); gravity in the base frame.
    KdlDynamics(const std::vector<KdlLink>& links, const std::array<double, 3>& gravity);
    ~KdlDynamics();
    KdlDynamics(const KdlDynamics&) = delete;
    KdlDynamics& operator=(const KdlDynamics&) = delete;

    int joint_count() const;
    // ChainIdSolver_RNE: tau for (q, qd, qdd), no external wrenches. False when KDL reports an error.
    bool inverse_dynamics(const double* q, const double* qd, const double* qdd, double* tau);
    // ChainFdSolver_RNE: qdd for (q, qd, tau), no external wrenches. False when KDL reports an error.
    bool forward_dynamics(const double* q, const double* qd, const double* tau, double* qdd);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace jacobid::test
