// SPDX-License-Identifier: MIT
#pragma once
// The excitation trajectory of `jacobid excite` (docs/excite.md): per joint a finite Fourier series
// (Swevers, Ganseman, Tukel, De Schutter, Van Brussel 1997),
//     qd_j(t) = sum_{l=1..L} a_jl cos(l w t) + b_jl sin(l w t),   w = 2 pi f (the base frequency),
// integrated to q_j(t) = q0_j + sum_l a_jl / (l w) sin(l w t) - b_jl / (l w) cos(l w t), each basis function
// corrected by the quintic polynomial that gives it zero position, velocity and acceleration at t = 0 and at
// t = T (the period played). So every period starts and ends at rest at the pose q0, periods can be played
// back to back, and q, qd, qdd are linear in the coefficients c = (a_j1 b_j1 .. a_jL b_jL)_j: what the
// optimizer's constraints and gradients use.
#include <Eigen/Core>
#include <vector>

namespace jacobid::excite {

class FourierBasis {
public:
    // period T (s) > 0, harmonics L >= 1, base frequency f (Hz) > 0.
    FourierBasis(double period, int harmonics, double base_frequency);

    double period() const { return period_; }
    int harmonics() const { return harmonics_; }
    double base_frequency() const { return frequency_; }
    int size() const { return 2 * harmonics_; }  // coefficients per joint

    // The corrected basis functions at t in [0, T] (psi_k, psi_k', psi_k''), each of size(); t outside
    // [0, T] is taken modulo T (periods back to back).
    void evaluate(double t, Eigen::Ref<Eigen::VectorXd> psi, Eigen::Ref<Eigen::VectorXd> dpsi, Eigen::Ref<Eigen::VectorXd> ddpsi) const;

private:
    double period_, frequency_;
    int harmonics_;
    // Per basis function, the six coefficients of its quintic correction (in powers of s = t / T).
    Eigen::MatrixXd correction_;
};

// One joint's coefficients and pose, with the joint's position, velocity and acceleration at t.
struct JointState {
    double q = 0.0, qd = 0.0, qdd = 0.0;
};

// The trajectory of all joints: pose q0 (rad) and coefficients (joints x size(), row j = joint j's
// a_1 b_1 .. a_L b_L).
struct FourierTrajectory {
    FourierBasis basis;
    Eigen::VectorXd pose;
    Eigen::MatrixXd coefficients;

    int joints() const { return static_cast<int>(pose.size()); }
    // Every joint at t (periods back to back).
    void evaluate(double t, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd, Eigen::Ref<Eigen::VectorXd> qdd) const;
};

}  // namespace jacobid::excite
