// SPDX-License-Identifier: MIT
#include "excite/fourier_trajectory.hpp"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

namespace jacobid::excite {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The raw (uncorrected) basis function k at t and its two derivatives: k = 2 (l - 1) is a_l's, k + 1 b_l's.
void raw(int k, double omega, double t, double& f, double& df, double& ddf) {
    const double lw = (k / 2 + 1) * omega;
    const double s = std::sin(lw * t), c = std::cos(lw * t);
    if (k % 2 == 0) {  // a_l: q = sin / (l w), qd = cos, qdd = -l w sin
        f = s / lw, df = c, ddf = -lw * s;
    } else {  // b_l: q = -cos / (l w), qd = sin, qdd = l w cos
        f = -c / lw, df = s, ddf = lw * c;
    }
}

}  // namespace

FourierBasis::FourierBasis(double period, int harmonics, double base_frequency)
    : period_(period), frequency_(base_frequency), harmonics_(harmonics) {
    if (!(period > 0.0) || harmonics < 1 || !(base_frequency > 0.0)) {
        throw std::invalid_argument("FourierBasis: period and base frequency must be > 0, harmonics >= 1");
    }
    // The quintic p(s) = sum_i p_i s^i, s = t / T, with p, p', p'' at both ends equal to minus the raw
    // function's: six linear conditions on its six coefficients (derivatives in t: d/dt = (1/T) d/ds).
    Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
    for (int i = 0; i < 6; ++i) {
        A(3, i) = 1.0;                                                   // p(1)
        A(4, i) = i / period;                                            // p'(1)
        A(5, i) = i * (i - 1) / (period * period);                       // p''(1)
    }
    A(0, 0) = 1.0;                        // p(0)
    A(1, 1) = 1.0 / period;               // p'(0)
    A(2, 2) = 2.0 / (period * period);    // p''(0)
    const Eigen::PartialPivLU<Eigen::Matrix<double, 6, 6>> lu(A);
    const double omega = 2.0 * kPi * frequency_;
    correction_.resize(6, size());
    for (int k = 0; k < size(); ++k) {
        Eigen::Matrix<double, 6, 1> rhs;
        raw(k, omega, 0.0, rhs[0], rhs[1], rhs[2]);
        raw(k, omega, period_, rhs[3], rhs[4], rhs[5]);
        correction_.col(k) = lu.solve(-rhs);
    }
}

void FourierBasis::evaluate(double t, Eigen::Ref<Eigen::VectorXd> psi, Eigen::Ref<Eigen::VectorXd> dpsi, Eigen::Ref<Eigen::VectorXd> ddpsi) const {
    t = std::fmod(t, period_);
    if (t < 0.0) t += period_;
    const double omega = 2.0 * kPi * frequency_, s = t / period_;
    double pw[6] = {1.0, s, s * s, s * s * s, s * s * s * s, s * s * s * s * s};
    for (int k = 0; k < size(); ++k) {
        double f, df, ddf;
        raw(k, omega, t, f, df, ddf);
        double p = 0.0, dp = 0.0, ddp = 0.0;
        for (int i = 0; i < 6; ++i) {
            const double ci = correction_(i, k);
            p += ci * pw[i];
            if (i >= 1) dp += ci * i * pw[i - 1] / period_;
            if (i >= 2) ddp += ci * i * (i - 1) * pw[i - 2] / (period_ * period_);
        }
        psi[k] = f + p, dpsi[k] = df + dp, ddpsi[k] = ddf + ddp;
    }
}

void FourierTrajectory::evaluate(double t, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd, Eigen::Ref<Eigen::VectorXd> qdd) const {
    Eigen::VectorXd psi(basis.size()), dpsi(basis.size()), ddpsi(basis.size());
    basis.evaluate(t, psi, dpsi, ddpsi);
    q = pose + coefficients * psi;
    qd = coefficients * dpsi;
    qdd = coefficients * ddpsi;
}

}  // namespace jacobid::excite
