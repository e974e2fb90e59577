// SPDX-License-Identifier: MIT
#include "diagnose/horizon_simulation.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace jacobid::diagnose {

HorizonResult simulate_horizons(const robot::RobotModel& model, const Eigen::VectorXd& x_in, const identify::LogColumns& log,
                                const identify::StateEstimates& e, double delay, const HorizonSettings& s) {
    const Eigen::VectorXd x = x_in.unaryExpr([](double v) { return std::isnan(v) ? 0.0 : v; });
    robot::ForwardDynamics dynamics(model, x);
    const int n = model.joint_count();
    const auto nj = static_cast<std::size_t>(n);
    const double h = log.sample_period;
    const auto length = static_cast<std::size_t>(std::llround(s.horizon / h));
    const auto spacing = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(s.spacing / h)));
    HorizonResult r;
    r.rms_error.assign(nj, 0.0);
    r.end_error.assign(nj, 0.0);
    std::size_t compared = 0;
    // Friction with memory (presliding): its state integrated along the measured positions, as the
    // identification integrates it, and its torque applied as known beside the measured one (a short open-loop
    // segment cannot carry the state itself: it starts from an unknown one).
    std::vector<std::vector<double>> held;  // per joint, full rate; empty: the model has none
    if (model.history_size() > 0) {
        std::vector<double> history;
        model.integrate_history(log.q, history);
        const auto width = static_cast<std::size_t>(model.history_size());
        held.assign(nj, std::vector<double>(log.samples(), 0.0));
        Eigen::MatrixXd D(n, model.parameter_count());
        for (std::size_t k = 0; k < log.samples(); ++k) {
            D.setZero();
            model.history_columns(history.data() + k * width, D);
            const Eigen::VectorXd f = D * x;
            for (std::size_t j = 0; j < nj; ++j) held[j][k] = f[static_cast<Eigen::Index>(j)];
        }
    }
    // Linear interpolation of a full-rate column at time index `at` (fractional), clamped to the log.
    auto interpolate = [&](const std::vector<double>& column, double at) {
        const double clamped = std::clamp(at, 0.0, static_cast<double>(log.samples() - 1));
        const auto i = static_cast<std::size_t>(std::floor(clamped));
        const std::size_t i1 = std::min(i + 1, log.samples() - 1);
        const double f = clamped - static_cast<double>(i);
        return (1.0 - f) * column[i] + f * column[i1];
    };
    // Measured torque at time index `at` (fractional), read `delay` later, less the held friction at `at`.
    Eigen::VectorXd tau(n);
    auto torque = [&](double at) {
        for (std::size_t j = 0; j < nj; ++j) {
            tau[static_cast<Eigen::Index>(j)] = interpolate(*log.tau[j], at + delay / h) - (held.empty() ? 0.0 : interpolate(held[j], at));
        }
    };
    Eigen::VectorXd q(n), qd(n), kq[4], kv[4], qs(n), vs(n);
    for (auto& k : kq) k.resize(n);
    for (auto& k : kv) k.resize(n);
    // Why a stage of the integration cannot go on: the reason is decided where the stage fails, from the
    // state it was given (never from a stage not yet computed, whose vectors hold nothing meaningful).
    const char* failure = nullptr;
    auto derivative = [&](double at, const Eigen::VectorXd& qq, const Eigen::VectorXd& vv, Eigen::VectorXd& dq, Eigen::VectorXd& dv) {
        torque(at);
        dq = vv;
        if (!qq.allFinite() || !vv.allFinite()) {
            failure = "no finite state";
            return false;
        }
        if (!dynamics.accelerations(qq.data(), vv.data(), tau.data(), dv.data())) {
            failure = "the identified inertia matrix is not positive definite along the path";
            return false;
        }
        return true;
    };
    std::vector<double> sum(nj), last(nj), end(nj, 0.0);
    std::size_t kept = 0;
    for (std::size_t k0 = e.first; k0 + length < e.last; k0 += spacing) {
        for (std::size_t j = 0; j < nj; ++j) {
            q[static_cast<Eigen::Index>(j)] = (*log.q[j])[k0];
            qd[static_cast<Eigen::Index>(j)] = e.qd[j][k0];
        }
        std::fill(sum.begin(), sum.end(), 0.0);
        DivergedSegment diverged;
        for (std::size_t step = 0; step < length && diverged.why.empty(); ++step) {
            const double at = static_cast<double>(k0 + step);
            bool ok = derivative(at, q, qd, kq[0], kv[0]);
            qs = q + 0.5 * h * kq[0];
            vs = qd + 0.5 * h * kv[0];
            ok = ok && derivative(at + 0.5, qs, vs, kq[1], kv[1]);
            qs = q + 0.5 * h * kq[1];
            vs = qd + 0.5 * h * kv[1];
            ok = ok && derivative(at + 0.5, qs, vs, kq[2], kv[2]);
            qs = q + h * kq[2];
            vs = qd + h * kv[2];
            ok = ok && derivative(at + 1.0, qs, vs, kq[3], kv[3]);
            if (!ok) {
                diverged = {log.start_time + static_cast<double>(k0) * h, static_cast<double>(step) * h, -1, failure};
                break;
            }
            q += h / 6.0 * (kq[0] + 2.0 * kq[1] + 2.0 * kq[2] + kq[3]);
            qd += h / 6.0 * (kv[0] + 2.0 * kv[1] + 2.0 * kv[2] + kv[3]);
            for (std::size_t j = 0; j < nj; ++j) {
                const double err = q[static_cast<Eigen::Index>(j)] - (*log.q[j])[k0 + step + 1];
                if (!(std::abs(err) <= s.diverged_at)) {
                    diverged = {log.start_time + static_cast<double>(k0) * h, static_cast<double>(step + 1) * h, static_cast<int>(j),
                                std::isfinite(err) ? fmt::format("left the measured path by more than {:g} rad", s.diverged_at) : "no finite state"};
                    break;
                }
                sum[j] += err * err;
                last[j] = err * err;
            }
        }
        ++r.segments;
        if (!diverged.why.empty()) {
            ++r.diverged;
            if (r.divergences.size() < HorizonResult::kMaxListed) r.divergences.push_back(diverged);
            continue;
        }
        for (std::size_t j = 0; j < nj; ++j) r.rms_error[j] += sum[j], end[j] += last[j];
        compared += length;
        ++kept;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t j = 0; j < nj; ++j) {
        r.rms_error[j] = compared ? std::sqrt(r.rms_error[j] / static_cast<double>(compared)) : nan;
        r.end_error[j] = kept ? std::sqrt(end[j] / static_cast<double>(kept)) : nan;
    }
    return r;
}

HorizonResult pooled_horizons(const std::vector<HorizonResult>& parts) {
    if (parts.size() == 1) return parts.front();
    HorizonResult r;
    const std::size_t joints = parts.empty() ? 0 : parts.front().rms_error.size();
    std::vector<double> rms2(joints, 0.0), end2(joints, 0.0);
    double kept = 0.0;
    for (const HorizonResult& p : parts) {
        r.segments += p.segments;
        r.diverged += p.diverged;
        for (const DivergedSegment& d : p.divergences) {
            if (r.divergences.size() < HorizonResult::kMaxListed) r.divergences.push_back(d);
        }
        const auto k = static_cast<double>(p.segments - p.diverged);
        if (k == 0.0) continue;  // its figures are NaN: nothing compared
        kept += k;
        for (std::size_t j = 0; j < joints; ++j) {
            rms2[j] += k * p.rms_error[j] * p.rms_error[j];
            end2[j] += k * p.end_error[j] * p.end_error[j];
        }
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t j = 0; j < joints; ++j) {
        r.rms_error.push_back(kept > 0.0 ? std::sqrt(rms2[j] / kept) : nan);
        r.end_error.push_back(kept > 0.0 ? std::sqrt(end2[j] / kept) : nan);
    }
    return r;
}

std::string HorizonResult::divergence_summary() const {
    if (diverged == 0) return "";
    const DivergedSegment& d = divergences.front();
    const std::string where = d.joint >= 0 ? fmt::format("joint {} after {:.3g} s", d.joint + 1, d.after) : fmt::format("after {:.3g} s", d.after);
    return fmt::format("{} of {} short-horizon segments diverged (first at t = {:.4g} s, {}: {}); excluded from the figure", diverged, segments, d.t,
                       where, d.why);
}

}  // namespace jacobid::diagnose
