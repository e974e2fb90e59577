// SPDX-License-Identifier: MIT
#include "identify/friction/torque_delay.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "identify/friction/torque_delay_std.hpp"
#include "identify/pipeline/row_collector.hpp"
#include "identify/pipeline/running_qr.hpp"
#include "identify/validation/validation.hpp"

namespace jacobid::identify {
double sample_at(const std::vector<double>& x, double at) {
    if (!(at > 0.0)) return x.front();
    const auto i = static_cast<std::size_t>(std::floor(at));
    if (i + 1 >= x.size()) return x.back();
    const double f = at - static_cast<double>(i);
    return (1.0 - f) * x[i] + f * x[i + 1];
}

namespace {

// x[k] = sample_at(x, k + shift) for every k, in place: a later sample is read before it is written when
// shift > 0 (forward), an earlier one when shift < 0 (backward), so every read sees the original value (the
// ends sample_at holds are written last in either order).
void shift_in_place(std::vector<double>& x, double shift) {
    if (shift > 0.0) {
        for (std::size_t k = 0; k < x.size(); ++k) x[k] = sample_at(x, static_cast<double>(k) + shift);
    } else {
        for (std::size_t k = x.size(); k-- > 0;) x[k] = sample_at(x, static_cast<double>(k) + shift);
    }
}

}  // namespace

ShiftedTorques shift_torques(const LogColumns& log, double delay) {
    ShiftedTorques s;
    s.log = log;
    s.log.own_tau.clear();  // the view never aligns them again
    s.log.tau_aligned_by = delay;
    if (delay == log.tau_aligned_by) return s;  // the log itself: no copy of its torques
    const double shift = (delay - log.tau_aligned_by) / log.sample_period;
    bool owned = log.own_tau.size() == log.tau.size();
    for (std::size_t j = 0; owned && j < log.tau.size(); ++j) owned = log.own_tau[j] == log.tau[j];
    if (owned) {
        for (std::vector<double>* x : log.own_tau) shift_in_place(*x, shift);
        return s;
    }
    s.tau.resize(log.tau.size());
    for (std::size_t j = 0; j < log.tau.size(); ++j) {
        const auto& x = *log.tau[j];
        s.tau[j].resize(x.size());
        for (std::size_t k = 0; k < x.size(); ++k) s.tau[j][k] = sample_at(x, static_cast<double>(k) + shift);
    }
    for (std::size_t j = 0; j < log.tau.size(); ++j) s.log.tau[j] = &s.tau[j];
    return s;
}

namespace {

// The factors of the torque read `shift` samples later, from the first identification's decimated rows and
// full-rate filtered torque (RowCollector); false when the rows were not kept or a shifted sample falls
// outside the filtered range. The regressor does not see the
// torque, and every filter the torque goes through (the Jacobi torque smoothing or F_q, then F_p) is linear
// and time-invariant, so the torque read i samples later gives the same rows W_k with Y = (filtered
// torque)[k + i]: the shifted identifications need only a QR each, not a regressor and F_p again (they were
// three of the search's four pipelines, which for a log shorter than max_samples cost 3 x identify's own fold).
// Compared with filtering the shifted torque itself, only the |i| samples at one end of the record differ
// (the shift held the end value there); they reach the kept rows only through the filters' cropped end
// transients (RSS within ~5e-7 relative with Jacobi, ~4e-6 with Butterworth's F_q, which pads the record from
// its end values; test TorqueDelay.ShiftedRowsEqualTheShiftedTorqueFilteredAgain).
bool shifted_factors(const RowCollector& rows, int shift, JointFactors& out) {
    if (!rows.complete() || rows.rows() == 0) return false;
    const std::vector<std::size_t>& samples = rows.samples();
    const auto lo = static_cast<long long>(samples.front()) + shift, hi = static_cast<long long>(samples.back()) + shift;
    if (lo < static_cast<long long>(rows.covered_from()) || hi >= static_cast<long long>(rows.covered_to())) return false;
    out = {};
    const std::size_t p = rows.parameters();
    std::vector<double> row(p + 1);
    for (std::size_t j = 0; j < rows.joints(); ++j) {
        RunningQr qr(static_cast<int>(p + 1));
        const std::vector<double>& w = rows.w(j);
        const std::vector<double>& filtered = rows.filtered_torque()[j];
        for (std::size_t m = 0; m < samples.size(); ++m) {
            std::copy(w.begin() + static_cast<std::ptrdiff_t>(m * p), w.begin() + static_cast<std::ptrdiff_t>((m + 1) * p), row.begin());
            row[p] = filtered[static_cast<std::size_t>(static_cast<long long>(samples[m]) + shift)];
            qr.add_row(row.data());
        }
        out.r.push_back(qr.r());
        out.rows.push_back(qr.rows());
    }
    return true;
}

}  // namespace

TorqueDelayEstimate estimate_torque_delay(const robot::RobotModel& model, const LogColumns& full_log, const PipelineSettings& pipeline,
                                          const SolveOptions& solve, const TorqueDelaySettings& settings) {
    TorqueDelayEstimate e;
    // A constant offset is as visible in the first max_samples as in the whole log: long logs are estimated
    // on their beginning so that the search costs a few identifications of bounded size, not of the hour.
    std::vector<std::vector<double>> head;
    LogColumns log = full_log;
    if (settings.max_samples > 0 && full_log.samples() > settings.max_samples) {
        for (const auto* columns : {&full_log.q, &full_log.tau}) {
            for (const auto* c : *columns) head.emplace_back(c->begin(), c->begin() + static_cast<std::ptrdiff_t>(settings.max_samples));
        }
        log.qd.clear();  // logged velocities are not used by the search
        for (std::size_t j = 0; j < log.q.size(); ++j) log.q[j] = &head[j];
        for (std::size_t j = 0; j < log.tau.size(); ++j) log.tau[j] = &head[log.q.size() + j];
        e.samples_used = settings.max_samples;
    } else {
        e.samples_used = full_log.samples();
    }
    if (pipeline.progress) fmt::print(stderr, "identify: estimating the torque delay on {} samples\n", e.samples_used);
    const double h = log.sample_period;
    const double max_delay = settings.max_delay > 0.0 ? settings.max_delay : 5.0 * h;
    PipelineSettings quiet = pipeline;
    quiet.progress = false;
    quiet.plot_rows = 0;
    quiet.residual_lags = 0;  // only RSS is compared: no standard deviations, no lagged products
    // The first identification fixes the automatic choices (bandwidth, windows, decimation) so that every
    // shifted torque is fitted with the same equations and RSS values are comparable.
    RowCollectorSettings keep;
    keep.max_values = std::size_t{8} << 20;  // 64 MB of rows; past it the search filters each shifted torque instead
    RowCollector rows(log.q.size(), log.samples(), keep);
    const PipelineOutput first = run_pipeline(model, log, quiet, &rows);
    quiet = validation_settings(quiet, first.info);
    const std::vector<std::string>& names = model.parameter_names();
    std::size_t equations = 0;
    int parameters = 0;
    JointFactors shifted;
    std::map<int, LsSolution> fits;  // by shift in samples: the std needs the minimum's and its neighbours'
    const auto rss_at = [&](double d) {
        ++e.evaluations;
        const int samples = static_cast<int>(std::lround(d / h));
        const JointFactors& factors = d == 0.0                        ? first.factors
                                      : shifted_factors(rows, samples, shifted) ? shifted
                                                                       : (shifted = run_pipeline(model, shift_torques(log, d).log, quiet).factors);
        const LsSolution& s = fits[samples] = solve_least_squares(factors, names, solve);
        equations = s.equations;
        parameters = s.identified_count;
        return s.residual_norm * s.residual_norm;
    };
    const int half = std::max(1, static_cast<int>(std::lround(max_delay / h)));
    // Grid of one sample, walked outwards from 0 while RSS keeps falling (smooth, unimodal near the truth).
    e.grid.push_back(0.0);
    e.rss.push_back(rss_at(0.0));
    for (const int direction : {-1, 1}) {
        for (int i = 1; i <= half; ++i) {
            const double d = direction * i * h;
            const double r = rss_at(d);
            const auto at = direction < 0 ? e.grid.begin() : e.grid.end();
            const auto offset = at - e.grid.begin();
            e.grid.insert(at, d);
            e.rss.insert(e.rss.begin() + offset, r);
            const double previous = direction < 0 ? e.rss[1] : e.rss[e.rss.size() - 2];
            if (r > previous) break;  // past the minimum on this side
        }
    }
    const auto best = static_cast<std::size_t>(std::min_element(e.rss.begin(), e.rss.end()) - e.rss.begin());
    e.delay = e.grid[best];
    double curvature = 0.0;
    if (best == 0 || best + 1 == e.grid.size()) {
        e.at_bound = std::abs(e.grid[best]) >= half * h * (1.0 - 1e-9);
    } else {
        const double rm = e.rss[best - 1], rc = e.rss[best], rp = e.rss[best + 1];
        const double den = rm - 2.0 * rc + rp;
        if (den > 0.0) {
            e.delay += 0.5 * h * (rm - rp) / den;
            curvature = den / (h * h);
        }
    }
    DelayScoreVariance score;
    if (curvature > 0.0) {
        const int shift = static_cast<int>(std::lround(e.grid[best] / h));
        const ShiftedFit around[3] = {{shift - 1, &fits.at(shift - 1)}, {shift, &fits.at(shift)}, {shift + 1, &fits.at(shift + 1)}};
        score = torque_delay_score_variance(rows, around, h, e.delay, curvature);
    }
    if (score.rows > 0) {
        e.std_lags = score.lags;
        e.std_dev = std::sqrt(score.variance) / (0.5 * curvature);
    } else {
        // The rows were not kept (a log whose rows exceed keep.max_values): the independent-rows std, which the
        // rows' serial correlation makes about 2 x too small (std_lags 0; docs/method.md).
        const double dof = static_cast<double>(equations) - static_cast<double>(parameters) - 1.0;
        const double sigma2 = dof > 0.0 ? e.rss[best] / dof : std::numeric_limits<double>::infinity();
        e.std_dev = curvature > 0.0 ? std::sqrt(2.0 * sigma2 / curvature) : std::numeric_limits<double>::infinity();
    }
    e.compensated = std::abs(e.delay) > settings.significance * e.std_dev;
    return e;
}

std::string describe(const TorqueDelayResult& r) {
    const TorqueDelayEstimate& e = r.estimate;
    if (r.given) return fmt::format("torque delay {:+.3f} ms (given by --torque-delay)", 1e3 * e.delay);
    // No curvature at the minimum (at the edge of the search range, or a flat cost): the std is unknown,
    // said in words rather than printed as "inf" (JSON: null).
    const std::string std_text = std::isfinite(e.std_dev) ? fmt::format("std {:.3f} ms", 1e3 * e.std_dev) : std::string("std unknown");
    std::string s = fmt::format("torque delay {:+.3f} ms ({}, estimated from {} identifications of {} samples; ", 1e3 * e.delay, std_text,
                                e.evaluations, e.samples_used);
    if (e.at_bound) return s + "at the edge of the search range: the offset may be larger; not compensated)";
    return s + (e.compensated ? "compensated)" : "not significant, not compensated)");
}

}  // namespace jacobid::identify
