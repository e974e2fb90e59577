// SPDX-License-Identifier: MIT
#include "identify/plan/periodic_log.hpp"

#include <fftw3.h>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "core/errors.hpp"
#include "signal/fftw_planner.hpp"

namespace jacobid::identify {
namespace {

// The motion has decorrelated once the mismatch exceeds this (a sine: a sixth of its period) ...
constexpr double kDecorrelated = 0.5;
// ... and repeats where it falls below this again: noise and small period-to-period differences stay far
// below (white position noise of 1 % of the motion's RMS adds 1e-4).
constexpr double kRepeats = 0.05;
// A given period may miss a whole number of samples by this much, accumulated over the averaged periods.
constexpr double kMaxDriftSamples = 0.25;
// A period whose positions deviate from the mean of all by more than this many times the median period's
// deviation is not the same motion (the start-up transient of a robot that starts at rest, a disturbance).
constexpr double kOutlierPeriod = 3.0;

// sum_k x[k] x[k + lag] for every lag in [0, n), by FFT (zero-padded: no circular wrap).
std::vector<double> autocorrelation_sums(const std::vector<double>& x) {
    const std::size_t n = x.size();
    std::size_t nfft = 1;
    while (nfft < 2 * n) nfft *= 2;
    std::vector<double> buffer(nfft, 0.0);
    std::copy(x.begin(), x.end(), buffer.begin());
    auto* spectrum = static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * (nfft / 2 + 1)));
    std::unique_ptr<fftw_complex, decltype(&fftw_free)> guard(spectrum, &fftw_free);
    fftw_plan forward = nullptr, backward = nullptr;
    {
        const std::lock_guard<std::mutex> lock(signal::fftw_planner_mutex());
        forward = fftw_plan_dft_r2c_1d(static_cast<int>(nfft), buffer.data(), spectrum, FFTW_ESTIMATE);
        backward = fftw_plan_dft_c2r_1d(static_cast<int>(nfft), spectrum, buffer.data(), FFTW_ESTIMATE);
    }
    fftw_execute(forward);
    for (std::size_t k = 0; k < nfft / 2 + 1; ++k) {
        spectrum[k][0] = spectrum[k][0] * spectrum[k][0] + spectrum[k][1] * spectrum[k][1];
        spectrum[k][1] = 0.0;
    }
    fftw_execute(backward);
    {
        const std::lock_guard<std::mutex> lock(signal::fftw_planner_mutex());
        fftw_destroy_plan(forward);
        fftw_destroy_plan(backward);
    }
    std::vector<double> sums(n);
    for (std::size_t lag = 0; lag < n; ++lag) sums[lag] = buffer[lag] / static_cast<double>(nfft);
    return sums;
}

struct ColumnAverage {
    std::vector<double> mean;  // one period
    double spread_variance = 0.0;  // about the mean, unbiased over the periods
};

// The mean of x over the given periods (indices of whole periods from the log's start) and their spread.
ColumnAverage average_column(const std::vector<double>& x, std::size_t period, const std::vector<std::size_t>& periods) {
    ColumnAverage a;
    a.mean.assign(period, 0.0);
    for (std::size_t m : periods) {
        for (std::size_t k = 0; k < period; ++k) a.mean[k] += x[m * period + k];
    }
    for (double& v : a.mean) v /= static_cast<double>(periods.size());
    double ss = 0.0;
    for (std::size_t m : periods) {
        for (std::size_t k = 0; k < period; ++k) ss += (x[m * period + k] - a.mean[k]) * (x[m * period + k] - a.mean[k]);
    }
    a.spread_variance = ss / (static_cast<double>(period) * static_cast<double>(periods.size() - 1));
    return a;
}

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

// The whole periods that repeat one motion: each period's RMS position deviation from the mean of all,
// per joint relative to the median period's, must stay within kOutlierPeriod. Returns the indices kept.
std::vector<std::size_t> consistent_periods(const LogColumns& log, std::size_t period, std::size_t periods) {
    std::vector<std::size_t> all(periods);
    for (std::size_t m = 0; m < periods; ++m) all[m] = m;
    if (periods < 3) return all;  // two periods deviate alike from their mean: nothing to tell them apart
    std::vector<double> score(periods, 0.0);
    for (const auto* column : log.q) {
        const ColumnAverage a = average_column(*column, period, all);
        std::vector<double> deviation(periods, 0.0);
        for (std::size_t m = 0; m < periods; ++m) {
            for (std::size_t k = 0; k < period; ++k) deviation[m] += ((*column)[m * period + k] - a.mean[k]) * ((*column)[m * period + k] - a.mean[k]);
            deviation[m] = std::sqrt(deviation[m] / static_cast<double>(period));
        }
        const double typical = median(deviation);
        for (std::size_t m = 0; m < periods; ++m) {
            if (typical > 0.0) score[m] = std::max(score[m], deviation[m] / typical);
            else if (deviation[m] > 0.0) score[m] = std::numeric_limits<double>::infinity();
        }
    }
    std::vector<std::size_t> kept;
    for (std::size_t m = 0; m < periods; ++m) {
        if (score[m] <= kOutlierPeriod) kept.push_back(m);
    }
    return kept;
}

std::vector<double> tiled(const std::vector<double>& period, int tiles) {
    std::vector<double> out;
    out.reserve(period.size() * static_cast<std::size_t>(tiles));
    for (int t = 0; t < tiles; ++t) out.insert(out.end(), period.begin(), period.end());
    return out;
}

// The whole-log mismatch also compares the log's start (a ramp from rest, a settling loop) with the
// periods after it, which can move its minimum by samples (a 1 s ramp before a 4 s period: 4002 instead
// of 4000, and the periods then drift through the average). Around the coarse period the mismatch is
// recomputed without the first period when the log holds three.
DetectedPeriod refine_period(const std::vector<std::vector<double>>& x, DetectedPeriod coarse, std::size_t longest) {
    const std::size_t n = x.front().size();
    if (n < 3 * coarse.samples) return coarse;
    const std::size_t reach = std::max<std::size_t>(2, std::min<std::size_t>(coarse.samples / 50, 50));
    const std::size_t from = coarse.samples > reach + 2 ? coarse.samples - reach : 2;
    const std::size_t to = std::min(longest, coarse.samples + reach);
    DetectedPeriod best{coarse.samples, 2.0};
    for (std::size_t lag = from; lag <= to; ++lag) {
        double difference = 0.0, both = 0.0;
        for (const auto& v : x) {
            for (std::size_t k = coarse.samples; k + lag < n; ++k) {
                difference += (v[k + lag] - v[k]) * (v[k + lag] - v[k]);
                both += v[k + lag] * v[k + lag] + v[k] * v[k];
            }
        }
        const double m = both > 0.0 ? difference / both : 1.0;
        if (m < best.mismatch) best = {lag, m};
    }
    return best;
}

}  // namespace

DetectedPeriod detect_period(const LogColumns& log, double min_joint_motion) {
    const std::size_t n = log.samples();
    std::vector<double> cross(n, 0.0), energy(n, 0.0);
    std::vector<std::vector<double>> normalized;  // the moving joints' positions, centred and scaled
    for (const auto* column : log.q) {
        const auto [lo, hi] = std::minmax_element(column->begin(), column->end());
        if (*hi - *lo < min_joint_motion) continue;
        double mean = 0.0;
        for (double v : *column) mean += v;
        mean /= static_cast<double>(n);
        double variance = 0.0;
        for (double v : *column) variance += (v - mean) * (v - mean);
        variance /= static_cast<double>(n);
        // Each moving joint counts alike, whatever its amplitude.
        std::vector<double> x(n);
        for (std::size_t k = 0; k < n; ++k) x[k] = (*column)[k] - mean;
        for (double& v : x) v /= std::sqrt(variance);
        const std::vector<double> s = autocorrelation_sums(x);
        for (std::size_t lag = 0; lag < n; ++lag) cross[lag] += s[lag];
        for (std::size_t k = 0; k < n; ++k) energy[k] += x[k] * x[k];
        normalized.push_back(std::move(x));
    }
    if (normalized.empty()) throw InputError(fmt::format("{}: --period auto: no joint moves, so no period can be detected", log.source));
    std::vector<double> energy_prefix(n + 1, 0.0);
    for (std::size_t k = 0; k < n; ++k) energy_prefix[k + 1] = energy_prefix[k] + energy[k];
    // mismatch(L) = sum (x[k + L] - x[k])^2 / sum (x[k + L]^2 + x[k]^2) over k < n - L.
    auto mismatch = [&](std::size_t lag) {
        const double both = energy_prefix[n - lag] + (energy_prefix[n] - energy_prefix[lag]);
        return both > 0.0 ? 1.0 - 2.0 * cross[lag] / both : 1.0;
    };
    const std::size_t longest = n / 2;  // two periods at least
    std::size_t lag = 1;
    while (lag <= longest && mismatch(lag) < kDecorrelated) ++lag;
    const std::size_t decorrelated = lag;
    DetectedPeriod best{0, 2.0};
    for (; lag <= longest; ++lag) {
        const double m = mismatch(lag);
        if (m < kRepeats) {
            // The whole basin below the threshold; its minimum is the period, refined without the log's start.
            for (; lag <= longest && mismatch(lag) < kRepeats; ++lag) {
                if (mismatch(lag) < best.mismatch) best = {lag, mismatch(lag)};
            }
            return refine_period(normalized, best, longest);
        }
        // The closest return, reported if none is close enough: from twice the decorrelation lag on, past the
        // motion's own short-lag similarity.
        if (lag >= 2 * decorrelated && m < best.mismatch) best = {lag, m};
    }
    throw InputError(fmt::format("{}: --period auto: the positions do not repeat within half the log (closest return: mismatch {:.3g} at a lag of {:.6g} s; "
                                 "a periodic log gives < {}); give --period SECONDS, or leave --period off",
                                 log.source, std::min(best.mismatch, 1.0), static_cast<double>(best.samples) * log.sample_period, kRepeats));
}

std::unique_ptr<PeriodicLog> average_periods(const LogColumns& log, std::optional<double> period, double min_joint_motion, int tiles) {
    auto out = std::make_unique<PeriodicLog>();
    PeriodicLog& p = *out;
    const std::size_t n = log.samples();
    const double ts = log.sample_period;
    if (period) {
        const double ratio = *period / ts;
        const auto whole = static_cast<long long>(std::llround(ratio));
        if (whole < 2) throw InputError(fmt::format("--period {} s: shorter than two samples of {} ({} s)", *period, log.source, ts));
        p.samples_per_period = static_cast<std::size_t>(whole);
        const std::size_t periods = n / p.samples_per_period;
        const double drift = std::abs(ratio - static_cast<double>(whole)) * static_cast<double>(periods);
        if (drift > kMaxDriftSamples) {
            throw InputError(fmt::format("--period {} s is {:.6g} samples of {} ({} s each): not a whole number, the periods would drift by {:.3g} "
                                         "samples over the log (at most {}); give a multiple of the sample period",
                                         *period, ratio, log.source, ts, drift, kMaxDriftSamples));
        }
    } else {
        const DetectedPeriod d = detect_period(log, min_joint_motion);
        p.samples_per_period = d.samples;
        p.detected = true;
        p.detection_mismatch = d.mismatch;
    }
    const std::size_t N = p.samples_per_period;
    p.period = static_cast<double>(N) * ts;
    p.periods = n / N;
    if (p.periods < 2) {
        throw InputError(fmt::format("--period {:.6g} s: {} holds {:.3g} periods ({} samples); averaging needs at least two whole periods", p.period,
                                     log.source, static_cast<double>(n) / static_cast<double>(N), n));
    }
    p.dropped_samples = n - p.periods * N;
    const std::vector<std::size_t> used = consistent_periods(log, N, p.periods);
    for (std::size_t m = 0, u = 0; m < p.periods; ++m) {
        if (u < used.size() && used[u] == m) ++u;
        else p.skipped_periods.push_back(m + 1);
    }
    if (used.size() < 2) {
        throw InputError(fmt::format("--period {:.6g} s: of the {} whole periods of {}, fewer than two repeat one motion (their positions differ "
                                     "by more than {} x the typical period's spread); averaging needs two",
                                     p.period, p.periods, log.source, kOutlierPeriod));
    }
    if (!p.skipped_periods.empty()) {
        std::string list;
        for (std::size_t m : p.skipped_periods) list += fmt::format("{}{}", list.empty() ? "" : ", ", m);
        p.warnings.push_back(fmt::format("--period {:.6g} s: period(s) {} of {} not averaged: their positions deviate from the others' by more than "
                                         "{} x the typical spread (a start-up transient, a disturbance)",
                                         p.period, list, p.periods, kOutlierPeriod));
    }
    const std::size_t joints = log.q.size();
    auto average_into = [&](const std::vector<const std::vector<double>*>& in, std::vector<std::vector<double>>& owned, std::vector<double>* noise) {
        owned.assign(in.size(), {});
        for (std::size_t j = 0; j < in.size(); ++j) {
            if (!in[j]) continue;
            ColumnAverage a = average_column(*in[j], N, used);
            if (noise) noise->push_back(std::sqrt(a.spread_variance));
            owned[j] = tiled(a.mean, tiles);
        }
    };
    average_into(log.q, p.q, &p.position_noise);
    average_into(log.tau, p.tau, &p.torque_noise);
    average_into(log.qd, p.qd, nullptr);
    average_into(log.q_ref, p.q_ref, nullptr);
    average_into(log.qd_ref, p.qd_ref, nullptr);

    LogColumns& c = p.columns;
    c.source = fmt::format("{} (mean of {} periods of {:.6g} s)", log.source, used.size(), p.period);
    c.sample_period = ts;
    p.kept_from = static_cast<std::size_t>(tiles / 2) * N;
    p.kept_to = p.kept_from + N;
    c.start_time = log.start_time - static_cast<double>(p.kept_from) * ts;
    auto pointers = [](const std::vector<const std::vector<double>*>& in, const std::vector<std::vector<double>>& owned) {
        std::vector<const std::vector<double>*> view;
        for (std::size_t j = 0; j < in.size(); ++j) view.push_back(in[j] ? &owned[j] : nullptr);
        return view;
    };
    c.q = pointers(log.q, p.q);
    c.tau = pointers(log.tau, p.tau);
    c.qd = pointers(log.qd, p.qd);
    c.q_ref = pointers(log.q_ref, p.q_ref);
    c.qd_ref = pointers(log.qd_ref, p.qd_ref);
    c.q_names = log.q_names;
    c.tau_names = log.tau_names;

    // A period that does not close (wrong period, drift, a joint that does not return) puts a step at every
    // tile boundary, which the differentiators turn into spikes: say so.
    for (std::size_t j = 0; j < joints; ++j) {
        const std::vector<double>& q = p.q[j];
        double largest_step = 0.0;
        for (std::size_t k = 1; k < N; ++k) largest_step = std::max(largest_step, std::abs(q[k] - q[k - 1]));
        const double jump = std::abs(q[0] - q[N - 1]);
        p.wrap_jump.push_back(jump);
        const double allowed = 5.0 * largest_step + 5.0 * p.position_noise[j] / std::sqrt(static_cast<double>(used.size()));
        if (jump > allowed && jump > 0.0) {
            p.warnings.push_back(fmt::format("--period {:.6g} s: joint {}'s mean period ends {:.3g} from where it starts (largest step inside it "
                                             "{:.3g}): the log may not repeat with this period; derivatives near the period's ends are wrong",
                                             p.period, j + 1, jump, largest_step));
        }
    }
    return out;
}

PipelineSettings periodic_settings(PipelineSettings settings, const PeriodicLog& periodic) {
    settings.kept_from = periodic.kept_from;
    settings.kept_to = periodic.kept_to;
    return settings;
}

std::string describe(const PeriodicLog& p) {
    std::string noise;
    for (std::size_t j = 0; j < p.torque_noise.size(); ++j) noise += fmt::format("{}{:.3g}", j ? " " : "", p.torque_noise[j]);
    const std::size_t averaged = p.periods - p.skipped_periods.size();
    return fmt::format("periodic log: period {:.6g} s ({}{} samples), mean of {} of its {} whole periods ({} samples after the last one not used); "
                       "torque noise from the period-to-period spread, per joint: {} (the mean's: / {:.3g})",
                       p.period, p.detected ? "detected, " : "", p.samples_per_period, averaged, p.periods, p.dropped_samples, noise,
                       std::sqrt(static_cast<double>(averaged)));
}

nlohmann::json to_json(const PeriodicLog& p) {
    nlohmann::json j;
    j["seconds"] = p.period;
    j["samples"] = p.samples_per_period;
    j["detected"] = p.detected;
    if (p.detected) j["detection_mismatch"] = p.detection_mismatch;
    j["periods"] = p.periods;
    j["averaged_periods"] = p.periods - p.skipped_periods.size();
    j["skipped_periods"] = p.skipped_periods;
    j["dropped_samples"] = p.dropped_samples;
    j["torque_noise"] = p.torque_noise;
    j["position_noise"] = p.position_noise;
    j["wrap_jump"] = p.wrap_jump;
    j["warnings"] = p.warnings;
    return j;
}

std::optional<double> parse_period_option(const std::string& text) {
    if (text == "auto") return std::nullopt;
    std::size_t used = 0;
    double value = 0.0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || !std::isfinite(value) || value <= 0.0) {
        throw InputError(fmt::format("--period {}: expected auto or a period in seconds > 0", text));
    }
    return value;
}

}  // namespace jacobid::identify
