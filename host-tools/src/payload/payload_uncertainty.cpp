// SPDX-License-Identifier: MIT
#include "payload/payload_uncertainty.hpp"

#include <fmt/core.h>

#include <string>

namespace jacobid::payload {

void add_inherited_uncertainty(PayloadEstimate& out, const identify::JointFactors& solved, const std::vector<int>& free, const ArmModel& arm,
                               bool difference, const std::vector<double>& gain_std) {
    constexpr int kM = 9;
    const auto c = static_cast<int>(arm.values.size());
    const auto joints = static_cast<int>(solved.r.size());
    const auto nf = static_cast<Eigen::Index>(free.size());
    // Sensitivities through the weighted Gram matrix of the solved problem.
    const Eigen::MatrixXd r = identify::stacked_factor(solved, out.solution.joint_weights);
    const Eigen::MatrixXd gram = r.transpose() * r;
    Eigen::MatrixXd h(nf, nf);
    for (Eigen::Index a = 0; a < nf; ++a) {
        for (Eigen::Index b = 0; b < nf; ++b) h(a, b) = gram(free[a], free[b]);
    }
    const Eigen::LDLT<Eigen::MatrixXd> hinv(h);
    auto sensitivity = [&](Eigen::Index column) {
        Eigen::VectorXd g(nf);
        for (Eigen::Index a = 0; a < nf; ++a) g[a] = gram(free[a], column);
        return Eigen::VectorXd(hinv.solve(g));
    };
    if (arm.std_dev.size() == c && arm.std_dev.cwiseAbs().maxCoeff() > 0.0) {
        for (int p = 0; p < c; ++p) {
            const Eigen::VectorXd d = -sensitivity(10 + p) * arm.std_dev[p];
            for (Eigen::Index a = 0; a < nf; ++a) {
                for (Eigen::Index b = 0; b < nf; ++b) out.cov_arm(free[a], free[b]) += d[a] * d[b];
            }
        }
        out.included.push_back(fmt::format("the arm's parameter std from {} (independent: identify writes no correlations){}", arm.source,
                                           difference ? "; in the difference of the runs only where their motions differ" : ""));
    } else {
        out.left_out.push_back(fmt::format("the arm's parameter uncertainty: --arm {} gives no std (identify's --format json output does)", arm.source));
    }
    out.mass_gain_sensitivity.assign(static_cast<std::size_t>(joints), 0.0);
    for (int j = 0; j < joints; ++j) {
        const Eigen::VectorXd d = sensitivity(10 + c + j);
        for (Eigen::Index a = 0; a < nf; ++a) {
            if (free[a] == kM) out.mass_gain_sensitivity[static_cast<std::size_t>(j)] = d[a];
        }
        if (gain_std.empty()) continue;
        const double g = gain_std[static_cast<std::size_t>(j)];
        for (Eigen::Index a = 0; a < nf; ++a) {
            for (Eigen::Index b = 0; b < nf; ++b) out.cov_gain(free[a], free[b]) += d[a] * d[b] * g * g;
        }
    }
    if (gain_std.empty()) {
        out.left_out.push_back("the drive gains' uncertainty (give --gain-std, relative per joint; the mass's sensitivity to each gain is listed)");
    } else {
        // Against the arm model alone the arm is held while a gain moves, but it was identified with the same gains and
        // would move with them: there the gains' share is an upper bound (a common gain error scales arm and payload alike).
        // A std, not a bias: least-squares drive gains (identify --drive-gains' WLS/OLS) are pulled towards 0 by the
        // effort column's noise and model error, which no std holds (the UR10e pair: -10 to -16 % of mass).
        out.included.push_back(std::string(difference ? "the drive gains' relative std of --gain-std"
                                                      : "the drive gains' relative std of --gain-std, with the arm held (an upper bound: the arm, "
                                                        "identified with the same gains, would move with them)") +
                               " (their std only: a least-squares gain's pull towards 0 is not in it; docs/method.md, \"Payload identification\")");
    }

}

}  // namespace jacobid::payload
