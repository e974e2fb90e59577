// SPDX-License-Identifier: MIT
#pragma once
// Copies between Eigen vectors and KDL::JntArray, one element at a time through KDL's out-of-line
// operator(). Why not `array.data = v` or `return array.data`: Debian's liborocos-kdl is compiled for the
// default x86-64 target, so the JntArray storage it allocates is aligned to 16 bytes, while our code built
// with -march=native (AVX: EIGEN_MAX_ALIGN_BYTES 32) assumes 32-byte aligned dynamic storage and emits
// aligned AVX loads and stores for such an assignment. On a heap layout where KDL's buffer sits at an odd
// multiple of 16 that is a segfault (seen in UrdfExport.KdlTorques... on an AVX2 machine); scalar copies
// never assume an alignment.
#include <kdl/jntarray.hpp>

#include <Eigen/Core>

namespace jacobid::test {

inline KDL::JntArray to_kdl(const Eigen::VectorXd& v) {
    KDL::JntArray a(static_cast<unsigned>(v.size()));
    for (Eigen::Index j = 0; j < v.size(); ++j) a(static_cast<unsigned>(j)) = v[j];
    return a;
}

inline Eigen::VectorXd from_kdl(const KDL::JntArray& a) {
    Eigen::VectorXd v(static_cast<Eigen::Index>(a.rows()));
    for (unsigned j = 0; j < a.rows(); ++j) v[static_cast<Eigen::Index>(j)] = a(j);
    return v;
}

}  // namespace jacobid::test
