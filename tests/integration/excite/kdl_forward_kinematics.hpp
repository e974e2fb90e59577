// SPDX-License-Identifier: MIT
#pragma once
// orocos-kdl's forward kinematics (ChainFkSolverPos_recursive) of a serial chain, the independent reference
// of test_excite_workspace. Compiled in its own library without -march=native: Debian's KDL is built for
// 16-byte Eigen alignment, and KDL code compiled with AVX (32-byte) alignment crashes. So the interface
// carries plain arrays, no Eigen or KDL types.
#include <array>
#include <vector>

namespace jacobid::test {

// One joint as the chain describes it (kinematic_chain.hpp): the fixed transform from the antecedent's
// frame (rotation row-major, origin), then the motion about/along `axis` (in the joint frame).
struct PlainJoint {
    bool revolute = true;
    std::array<double, 9> rotation{};
    std::array<double, 3> position{}, axis{};
};

// The pose of joint `frame`'s frame (1-based: the tip of KDL segment `frame`) at q: rotation row-major,
// then the origin (12 values).
std::array<double, 12> kdl_frame_pose(const std::vector<PlainJoint>& chain, const std::vector<double>& q, int frame);

}  // namespace jacobid::test
