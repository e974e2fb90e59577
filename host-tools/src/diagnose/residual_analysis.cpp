// SPDX-License-Identifier: MIT
#include "diagnose/residual_analysis.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "diagnose/statistics.hpp"

namespace jacobid::diagnose {
namespace {

// Bins of `x` by the given edges (edges.size() - 1 bins), residual statistics in each.
std::vector<Bin> bin_by(const Eigen::VectorXd& r, const Eigen::VectorXd& x, const std::vector<double>& edges,
                        const std::vector<std::string>& labels) {
    std::vector<Bin> bins(edges.size() - 1);
    for (std::size_t b = 0; b < bins.size(); ++b) {
        bins[b].low = edges[b];
        bins[b].high = edges[b + 1];
        bins[b].label = b < labels.size() ? labels[b] : fmt::format("[{:.3g}, {:.3g})", edges[b], edges[b + 1]);
    }
    for (Eigen::Index i = 0; i < r.size(); ++i) {
        const auto it = std::upper_bound(edges.begin() + 1, edges.end() - 1, x[i]);
        Bin& b = bins[static_cast<std::size_t>(it - edges.begin() - 1)];
        ++b.count;
        b.mean += r[i];
        b.rms += r[i] * r[i];
    }
    for (auto& b : bins) {
        if (b.count == 0) continue;
        b.mean /= static_cast<double>(b.count);
        b.rms = std::sqrt(b.rms / static_cast<double>(b.count));
    }
    return bins;
}

std::vector<double> uniform_edges(double lo, double hi, int n) {
    std::vector<double> e;
    for (int i = 0; i <= n; ++i) e.push_back(lo + (hi - lo) * i / n);
    e.front() = -INFINITY;
    e.back() = INFINITY;
    return e;
}

std::vector<double> quantile_edges(Eigen::VectorXd x, int n) {
    std::sort(x.data(), x.data() + x.size());
    std::vector<double> e{-INFINITY};
    for (int i = 1; i < n; ++i) e.push_back(x[static_cast<Eigen::Index>((x.size() - 1) * i / n)]);
    e.push_back(INFINITY);
    return e;
}

std::vector<MotionStateBin> motion_states(const Eigen::VectorXd& r, const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd, double v0) {
    std::vector<MotionStateBin> states{{"at rest"}, {"reversing"}, {"moving"}};
    const double a0 = v0 / 0.2;
    const double total = r.squaredNorm();
    for (Eigen::Index i = 0; i < r.size(); ++i) {
        const std::size_t s = std::abs(qd[i]) >= v0 ? 2 : (std::abs(qdd[i]) >= a0 ? 1 : 0);
        ++states[s].count;
        states[s].mean += r[i];
        states[s].rms += r[i] * r[i];
    }
    for (auto& st : states) {
        st.row_share = r.size() > 0 ? static_cast<double>(st.count) / static_cast<double>(r.size()) : 0.0;
        st.energy_share = total > 0.0 ? st.rms / total : 0.0;
        if (st.count == 0) continue;
        st.mean /= static_cast<double>(st.count);
        st.rms = std::sqrt(st.rms / static_cast<double>(st.count));
    }
    return states;
}

const Bin& worst(const std::vector<Bin>& bins) {
    return *std::max_element(bins.begin(), bins.end(), [](const Bin& a, const Bin& b) { return std::abs(a.mean) < std::abs(b.mean); });
}

}  // namespace

JointResidualAnalysis analyse_residual(const Eigen::VectorXd& r, const Eigen::MatrixXd& state, const std::vector<double>& t, double v0,
                                       int max_order) {
    JointResidualAnalysis a;
    const Eigen::Index m = r.size();
    if (m < 8) return a;
    a.rms = std::sqrt(r.squaredNorm() / static_cast<double>(m));
    const Eigen::VectorXd q = state.col(0), qd = state.col(1), qdd = state.col(2);
    Eigen::VectorXd speed = qd.cwiseAbs();
    std::sort(speed.data(), speed.data() + m);
    const double v_mid = std::max(2.0 * v0, speed[m / 2]);
    a.velocity = bin_by(r, qd, {-INFINITY, -v_mid, -v0, v0, v_mid, INFINITY},
                        {fmt::format("qd < -{:.2g}", v_mid), fmt::format("-{:.2g} < qd < -{:.2g}", v_mid, v0), fmt::format("|qd| < {:.2g} (near zero)", v0),
                         fmt::format("{:.2g} < qd < {:.2g}", v0, v_mid), fmt::format("qd > {:.2g}", v_mid)});
    a.position = bin_by(r, q, uniform_edges(q.minCoeff(), q.maxCoeff(), 12), {});
    a.acceleration = bin_by(r, qdd, quantile_edges(qdd, 5), {});
    Eigen::VectorXd time = Eigen::Map<const Eigen::VectorXd>(t.data(), m);
    a.time = bin_by(r, time, uniform_edges(t.front(), t.back(), 10), {});

    // Spectrum against the angle: amplitude of the LS fit of a sin(k q) + b cos(k q) + c, per order.
    const Eigen::VectorXd rc = r.array() - r.mean();
    for (int k = 1; k <= max_order; ++k) {
        Eigen::MatrixXd B(m, 2);
        B.col(0) = (k * q.array()).sin();
        B.col(1) = (k * q.array()).cos();
        const Eigen::Vector2d c = B.colPivHouseholderQr().solve(rc);
        a.angle_orders.push_back(k);
        a.angle_amplitude.push_back(c.norm());
        if (c.norm() > a.dominant_amplitude) {
            a.dominant_amplitude = c.norm();
            a.dominant_order = k;
        }
    }
    a.motion = motion_states(r, qd, qdd, v0);
    a.autocorrelation = autocorrelation(r, 20);
    a.n_eff = effective_sample_size(r);

    const Bin& v = worst(a.velocity);
    a.findings.push_back(fmt::format("by velocity: largest mean residual {:+.3g} N.m at {} ({} rows)", v.mean, v.label, v.count));
    std::string states;
    for (const auto& st : a.motion) {
        if (st.count == 0) continue;
        states += fmt::format("{}{} {:.0f} % of rows, {:.0f} % of the residual energy (mean {:+.3g}, RMS {:.3g} N.m)", states.empty() ? "" : "; ",
                              st.state, 100.0 * st.row_share, 100.0 * st.energy_share, st.mean, st.rms);
    }
    a.findings.push_back("by motion state: " + states);
    const Bin& p = worst(a.position);
    a.findings.push_back(fmt::format("by position: largest mean residual {:+.3g} N.m at q in [{:.2f}, {:.2f}] rad", p.mean,
                                     std::max(p.low, q.minCoeff()), std::min(p.high, q.maxCoeff())));
    const Bin& ac = worst(a.acceleration);
    a.findings.push_back(fmt::format("by acceleration: largest mean residual {:+.3g} N.m at qdd in [{:.3g}, {:.3g}] rad/s^2", ac.mean,
                                     std::max(ac.low, qdd.minCoeff()), std::min(ac.high, qdd.maxCoeff())));
    const Bin& tb = worst(a.time);
    a.findings.push_back(fmt::format("by time: largest mean residual {:+.3g} N.m at t in [{:.1f}, {:.1f}] s", tb.mean, std::max(tb.low, t.front()),
                                     std::min(tb.high, t.back())));
    a.findings.push_back(fmt::format("vs angle: strongest periodic content at order {} per rev, amplitude {:.3g} N.m", a.dominant_order,
                                     a.dominant_amplitude));
    a.findings.push_back(fmt::format("whiteness: rho_1 = {:.2f}, effective sample size {:.0f} of {} rows{}",
                                     a.autocorrelation.empty() ? 0.0 : a.autocorrelation.front(), a.n_eff, m,
                                     strongly_correlated(a, static_cast<std::size_t>(m)) ? " (strongly correlated: structure left in the residual)" : ""));
    return a;
}

}  // namespace jacobid::diagnose
