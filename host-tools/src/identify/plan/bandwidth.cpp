// SPDX-License-Identifier: MIT
#include "identify/plan/bandwidth.hpp"

#include "core/errors.hpp"
#include "core/huge_pages.hpp"
#include "core/parallel_for.hpp"
#include "identify/plan/bandwidth_description.hpp"
#include "signal/fftw_planner.hpp"

#include <fftw3.h>
#include <fmt/core.h>

#include <algorithm>
#include <functional>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <utility>

namespace jacobid::identify {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Jump rule (docs/method.md): smooth motion never changes by 10 x its 99th-percentile step in one sample,
// and real motion lasts longer than 3 samples; a run of at most kJumpRun such differences is a break.
constexpr double kJumpFactor = 10.0;
constexpr std::size_t kJumpRun = 3;
// A joint counts when its motion's position variance is at least 100 x that of its noise floor (RMS 10 x).
constexpr double kMotionToNoise = 100.0;

// The p-quantile of `values`, which it reorders (nth_element).
double quantile_in_place(std::vector<double>& values, double p) {
    if (values.empty()) return 0.0;
    const auto k = static_cast<std::size_t>(p * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return values[k];
}

double quantile(const std::vector<double>& values, double p) {
    std::vector<double> v = values;
    return quantile_in_place(v, p);
}

// The first differences of q into `d`, with isolated jumps bridged by linear interpolation between the
// differences on either side; returns how many runs it bridged. The two selections (median step, 99th
// percentile of the deviations) share one scratch array, freed before d is made, and the deviations are
// computed again where the runs are sought: one whole-log array per joint at a time instead of four (each
// 29 MB for an hour at 1 kHz, one joint per thread: the identification's peak, docs/performance.md).
std::size_t bridged_differences(const std::vector<double>& q, std::vector<double>& d) {
    const std::size_t n = q.size() - 1;
    double median = 0.0, spread = 0.0;
    {
        std::vector<double> scratch = huge_vector<double>(n);
        for (std::size_t k = 0; k < n; ++k) scratch[k] = q[k + 1] - q[k];
        median = quantile_in_place(scratch, 0.5);
        for (std::size_t k = 0; k < n; ++k) scratch[k] = std::abs((q[k + 1] - q[k]) - median);
        spread = quantile_in_place(scratch, 0.99);
    }
    d = huge_vector<double>(n);
    for (std::size_t k = 0; k < n; ++k) d[k] = q[k + 1] - q[k];
    if (!(spread > 0.0)) return 0;  // 99 % of the log at one step: motion and jumps cannot be told apart
    const double threshold = kJumpFactor * spread;
    const auto deviation = [&](std::size_t k) { return std::abs(d[k] - median); };
    std::size_t runs = 0;
    for (std::size_t k = 0; k < d.size();) {
        if (deviation(k) <= threshold) {
            ++k;
            continue;
        }
        std::size_t end = k;
        while (end < d.size() && deviation(end) > threshold) ++end;
        if (end - k <= kJumpRun) {
            const double before = k > 0 ? d[k - 1] : (end < d.size() ? d[end] : median);
            const double after = end < d.size() ? d[end] : before;
            for (std::size_t i = k; i < end; ++i) {
                const double t = static_cast<double>(i - k + 1) / static_cast<double>(end - k + 1);
                d[i] = before + t * (after - before);
            }
            ++runs;
        }
        k = end;
    }
    return runs;
}

// Step of the grid the positions lie on: the smallest nonzero difference, if (nearly) every nonzero
// difference is a whole multiple of it; 0 otherwise (e.g. after interpolation onto a new time grid).
double quantization_step(const std::vector<double>& q) {
    double step = kInfinity;
    std::size_t nonzero = 0;
    for (std::size_t k = 1; k < q.size(); ++k) {
        const double a = std::abs(q[k] - q[k - 1]);
        if (a > 0.0) {
            step = std::min(step, a);
            ++nonzero;
        }
    }
    if (nonzero < 16 || !std::isfinite(step)) return 0.0;
    std::size_t on_grid = 0;
    for (std::size_t k = 1; k < q.size(); ++k) {
        const double r = std::abs(q[k] - q[k - 1]) / step;
        if (r > 0.0 && std::abs(r - std::round(r)) < 0.01) ++on_grid;
    }
    return static_cast<double>(on_grid) >= 0.95 * static_cast<double>(nonzero) ? step : 0.0;
}

// Joint j's label: names[j], or "joint j+1".
std::string joint_name(const std::vector<std::string>& names, std::size_t j) { return j < names.size() ? names[j] : fmt::format("joint {}", j + 1); }

// Whether a column changes at all (two adjacent samples differ).
bool varies(const std::vector<double>& x) { return std::adjacent_find(x.begin(), x.end(), std::not_equal_to<double>()) != x.end(); }

// f(j) for every joint j < count on up to `threads` threads; the first exception is rethrown.
template <class F>
void for_each_joint(std::size_t count, int threads, F&& f) {
    ParallelForOptions pool;
    pool.threads = threads;
    const auto errors = parallel_for(count, pool, std::forward<F>(f));
    for (const auto& e : errors) {
        if (e) std::rethrow_exception(e);
    }
}

// Welch spectrum (sum over segments) of the first difference `d`: segments of ~20 s (resolution 0.05 Hz),
// a power of two, at most the record, at most 64 spread over it (bounded cost on hour-long logs).
struct Welch {
    std::size_t seg = 0, hop = 0, segments = 0, used = 0;
    double window_power = 0.0;  // sum of w^2
    std::vector<double> window;
    Welch(std::size_t n, double ts) {
        seg = 256;
        while (seg * 2 <= n && static_cast<double>(seg) * ts < 20.0) seg *= 2;
        seg = std::min(seg, n);
        hop = seg / 2;
        segments = n >= seg ? (n - seg) / hop + 1 : 1;
        used = std::min<std::size_t>(segments, 64);
        window.resize(seg);
        for (std::size_t k = 0; k < seg; ++k) {
            window[k] = 0.5 - 0.5 * std::cos(2.0 * M_PI * static_cast<double>(k) / static_cast<double>(seg));
            window_power += window[k] * window[k];
        }
    }
    std::vector<double> power(const std::vector<double>& d) const {
        std::vector<double> in(seg), p(seg / 2 + 1, 0.0);
        auto* out = static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * (seg / 2 + 1)));
        std::unique_ptr<fftw_complex, decltype(&fftw_free)> out_guard(out, &fftw_free);
        fftw_plan plan = nullptr;
        {
            const std::lock_guard<std::mutex> lock(signal::fftw_planner_mutex());
            plan = fftw_plan_dft_r2c_1d(static_cast<int>(seg), in.data(), out, FFTW_ESTIMATE);
        }
        for (std::size_t s = 0; s < used; ++s) {
            const std::size_t start = used > 1 ? (segments - 1) * s / (used - 1) * hop : 0;
            double mean = 0.0;
            for (std::size_t k = 0; k < seg; ++k) mean += d[start + k];
            mean /= static_cast<double>(seg);
            for (std::size_t k = 0; k < seg; ++k) in[k] = (d[start + k] - mean) * window[k];
            fftw_execute(plan);
            for (std::size_t f = 0; f < p.size(); ++f) p[f] += out[f][0] * out[f][0] + out[f][1] * out[f][1];
        }
        {
            const std::lock_guard<std::mutex> lock(signal::fftw_planner_mutex());
            fftw_destroy_plan(plan);
        }
        return p;
    }
};

// The band a white floor's level is read from, 0.25..0.4 fs: above any motion a position loop follows (and
// the torque it takes), below the roll-off that interpolation onto a uniform grid or an anti-aliasing filter
// puts near fs / 2 (docs/method.md). Each bin sums `used` periodograms: chi-square with 2 x used degrees of
// freedom, whose median is nu (1 - 2 / (9 nu))^3 of its mean nu (Wilson-Hilferty).
struct FloorBand {
    std::size_t lo = 0, hi = 0;
    double median_to_mean = 1.0;
    FloorBand(const Welch& welch, double resolution, double fs) {
        const std::size_t bins = welch.seg / 2 + 1;
        lo = static_cast<std::size_t>(std::ceil(0.25 * fs / resolution));
        hi = std::min(bins - 1, static_cast<std::size_t>(std::floor(0.4 * fs / resolution)));
        const double nu = 2.0 * static_cast<double>(welch.used);
        median_to_mean = 1.0 / std::pow(1.0 - 2.0 / (9.0 * nu), 3.0);
    }
    bool usable() const { return hi > lo + 8; }
    // The mean level of p / shape over the band (shape: the floor's form, 1 for a white signal itself).
    double level(const std::vector<double>& p, const std::vector<double>* shape) const {
        if (!usable()) return 0.0;
        std::vector<double> ratio;
        for (std::size_t k = lo; k <= hi; ++k) ratio.push_back(shape ? p[k] / (*shape)[k] : p[k]);
        return quantile(ratio, 0.5) * median_to_mean;
    }
};

// The spectra of one joint (or of the sum over joints): velocity-difference power P, the noise floor F
// in it, and g = |1 - e^{-i 2 pi f Ts}|^2 (a white position noise of level L gives F = L g).
struct Spectrum {
    std::vector<double> power, floor, g;
    double level = 0.0;        // of the floor F
    double noise_level = 0.0;  // of the noise the bandwidth limit counts (>= level)
};

// First frequency where the cumulative sum of c (power minus floor) reaches `fraction` of its total; 0 when
// the total is not positive. Not clipped at 0 per bin: the noise's positive fluctuations about its floor
// would add up over thousands of bins (docs/method.md).
// Only bins up to `highest` count: above the widest differentiator cutoff the noise allows, a coloured
// floor (a coarse quantizer's) that the white model leaves behind would pass for motion.
double energy_frequency(const std::vector<double>& c, double resolution, double fraction, double highest) {
    const std::size_t bins = std::isfinite(highest) ? std::min(c.size(), static_cast<std::size_t>(highest / resolution) + 1) : c.size();
    double total = 0.0;
    for (std::size_t f = 0; f < bins; ++f) total += c[f];
    if (!(total > 0.0)) return 0.0;
    double cumulative = 0.0;
    for (std::size_t f = 0; f < bins; ++f) {
        cumulative += c[f];
        if (cumulative >= fraction * total) return std::max(static_cast<double>(f), 1.0) * resolution;
    }
    return static_cast<double>(bins - 1) * resolution;
}

// Highest bandwidth B whose differentiator cutoff (ratio x B) admits at most kAccelerationNoiseShare of
// floor in the acceleration energy: acceleration spectrum = position spectrum (P / g) x f^4, signal
// P - F, noise at noise_level (docs/method.md). The last cutoff that satisfies the bound, not the first
// that breaks it: below the lowest motion line the share is all noise. When no cutoff satisfies it, the
// cutoff with the smallest share. Infinity when the bound holds up to fs / 2.
double noise_limit(const Spectrum& s, double resolution, double ratio) {
    double signal = 0.0, noise = 0.0, best_share = kInfinity;
    std::size_t last_ok = 0, best = 1;
    for (std::size_t k = 1; k < s.power.size(); ++k) {
        const double f = static_cast<double>(k) * resolution;
        const double f4 = f * f * f * f;
        if (s.g[k] > 0.0) signal += (s.power[k] - s.floor[k]) / s.g[k] * f4;
        noise += s.noise_level * f4;
        const double share = signal > 0.0 ? noise / signal : kInfinity;
        if (share <= kAccelerationNoiseShare) last_ok = k;
        if (share < best_share) {
            best_share = share;
            best = k;
        }
    }
    if (last_ok + 1 == s.power.size()) return kInfinity;
    return static_cast<double>(last_ok > 0 ? last_ok + 1 : best) * resolution / ratio;
}

}  // namespace

BandwidthEstimate estimate_motion_bandwidth(const std::vector<const std::vector<double>*>& positions, double sample_period,
                                            const std::vector<std::string>& names, double cutoff_ratio, double fraction, int threads) {
    BandwidthEstimate result;
    if (positions.empty() || positions.front()->size() < 16) return result;
    const std::size_t n = positions.front()->size() - 1;  // differences
    const double ts = sample_period;
    const Welch welch(n, ts);
    const std::size_t bins = welch.seg / 2 + 1;
    result.resolution = 1.0 / (static_cast<double>(welch.seg) * ts);
    const double fs = 1.0 / ts;
    std::vector<double> g(bins);
    for (std::size_t k = 0; k < bins; ++k) {
        const double s = std::sin(M_PI * static_cast<double>(k) / static_cast<double>(welch.seg));
        g[k] = 4.0 * s * s;
    }
    const FloorBand band(welch, result.resolution, fs);

    // Each joint on its own (a few whole-log passes and two selections each: 1.5 s for an hour of 6 joints on
    // one thread), on up to `threads` threads; nothing is shared, so the result does not depend on them.
    std::vector<Spectrum> spectra(positions.size());
    result.joints.resize(positions.size());
    for_each_joint(positions.size(), threads, [&](std::size_t j) {
        const std::vector<double>& q = *positions[j];
        JointBandwidth& jb = result.joints[j];
        jb.name = joint_name(names, j);
        // A difference is nonzero exactly where two finite samples differ.
        jb.moving = varies(q);
        Spectrum s;
        s.g = g;
        if (jb.moving) {
            std::vector<double> d;
            jb.jumps = bridged_differences(q, d);
            jb.quantization_step = quantization_step(q);
            s.power = welch.power(d);
            s.level = band.level(s.power, &g);
            // A coarse quantizer's error is not white when the motion crosses few steps per sample: it
            // piles up at low frequencies, below the floor band, which then underestimates it there. Its
            // variance is D^2 / 12 all the same: a detected step sets the noise the bandwidth limit counts
            // to at least that, spread white. The floor subtracted from the velocity energy stays the band's:
            // D^2 / 12 spread white would over-subtract at high frequencies (docs/method.md).
            const double step = jb.quantization_step;
            s.noise_level = std::max(s.level, step * step / 12.0 * static_cast<double>(welch.used) * welch.window_power);
        } else {
            s.power.assign(bins, 0.0);
        }
        s.floor.resize(bins);
        double total = 0.0, removed = 0.0, motion_variance = 0.0;
        std::vector<double> clean(bins);
        for (std::size_t k = 0; k < bins; ++k) {
            s.floor[k] = s.level * g[k];
            clean[k] = s.power[k] - s.floor[k];
            total += s.power[k];
            removed += std::min(s.floor[k], s.power[k]);
            if (k > 0) motion_variance += std::max(clean[k], 0.0) / g[k];
        }
        jb.floor_fraction = total > 0.0 ? removed / total : 0.0;
        jb.noise_rms = std::sqrt(s.noise_level / (static_cast<double>(welch.used) * welch.window_power));
        jb.noise_limit = noise_limit(s, result.resolution, cutoff_ratio);
        jb.energy_frequency = energy_frequency(clean, result.resolution, fraction, cutoff_ratio * jb.noise_limit);
        jb.frequency = std::min(jb.energy_frequency, jb.noise_limit);
        jb.used = jb.moving && motion_variance >= kMotionToNoise * s.level * static_cast<double>(bins - 1);
        spectra[j] = std::move(s);
    });
    for (const auto& jb : result.joints) result.jumps += jb.jumps;
    const bool any_moving = std::any_of(result.joints.begin(), result.joints.end(), [](const JointBandwidth& j) { return j.moving; });
    if (!any_moving) return result;
    // Joints whose motion is lost in their own noise would only add noise; if every moving joint is such a
    // joint, they are all the information there is.
    const bool fallback = std::none_of(result.joints.begin(), result.joints.end(), [](const JointBandwidth& j) { return j.used; });
    result.all_below_floor = fallback;
    if (fallback) {
        for (auto& j : result.joints) j.used = j.moving;
    }
    // Combined over the joints used: spectra summed, so each joint weighs by its own motion energy.
    Spectrum sum;
    sum.g = g;
    sum.power.assign(bins, 0.0);
    sum.floor.assign(bins, 0.0);
    for (std::size_t j = 0; j < spectra.size(); ++j) {
        if (!result.joints[j].used) continue;
        sum.level += spectra[j].level;
        sum.noise_level += spectra[j].noise_level;
        for (std::size_t k = 0; k < bins; ++k) {
            sum.power[k] += spectra[j].power[k];
            sum.floor[k] += spectra[j].floor[k];
        }
    }
    std::vector<double> clean(bins);
    for (std::size_t k = 0; k < bins; ++k) clean[k] = sum.power[k] - sum.floor[k];
    result.noise_limit = noise_limit(sum, result.resolution, cutoff_ratio);
    result.energy_frequency = energy_frequency(clean, result.resolution, fraction, cutoff_ratio * result.noise_limit);
    if (!(result.energy_frequency > 0.0)) {
        throw InputError(fmt::format("the positions move but hold nothing above their noise floor ({}): no motion bandwidth can be estimated; "
                                     "give --bandwidth (the motion's bandwidth in Hz)", moving_joint_names(result.joints, true)));
    }
    result.moving = true;
    result.noise_limited = result.noise_limit < result.energy_frequency;
    result.frequency = std::min(result.energy_frequency, result.noise_limit);
    result.differentiator_frequency = result.frequency;
    result.description = describe_bandwidth(result, cutoff_ratio);
    return result;
}

TorqueBandwidth estimate_torque_bandwidth(const std::vector<const std::vector<double>*>& torques, double sample_period,
                                          const std::vector<std::string>& names, double highest, double fraction, int threads,
                                          const std::vector<double>& noise_std, double shift) {
    TorqueBandwidth result;
    if (torques.empty() || torques.front()->size() < 16) return result;
    if (!noise_std.empty() && noise_std.size() != torques.size()) {
        throw InputError(fmt::format("torque bandwidth: {} noise levels for {} torques", noise_std.size(), torques.size()));
    }
    const double fs = 1.0 / sample_period;
    const Welch welch(torques.front()->size(), sample_period);
    const std::size_t bins = welch.seg / 2 + 1;
    result.resolution = 1.0 / (static_cast<double>(welch.seg) * sample_period);
    const FloorBand band(welch, result.resolution, fs);
    // Bins from 0.25 fs up are the floor's by construction: torque there cannot be told from noise. The
    // variances (floor share, the joint's use) count bins up to the floor band's top, 0.4 fs.
    result.highest = std::min(highest, static_cast<double>(band.lo) * result.resolution);
    const std::size_t top = std::min(bins - 1, band.hi);
    result.noise_known = !noise_std.empty();
    // Torques read `shift` samples later by linear interpolation (identify's torque delay) went through
    // |H|^2 = (1 - a)^2 + a^2 + 2 a (1 - a) cos(2 pi f Ts), a the fractional part: divided out, so that
    // their white noise is white again (a = 0.5 keeps 10 % of it at 0.4 fs).
    const double a = shift - std::floor(shift);
    std::vector<double> interpolation(bins, 1.0);
    for (std::size_t k = 0; k < bins && a > 0.0; ++k) {
        const double c = std::cos(2.0 * M_PI * static_cast<double>(k) / static_cast<double>(welch.seg));
        interpolation[k] = std::max((1.0 - a) * (1.0 - a) + a * a + 2.0 * a * (1.0 - a) * c, 1e-12);
    }
    // A white noise of variance s^2 per sample puts s^2 x (segments x sum of w^2) in every bin of the sum.
    const double per_variance = static_cast<double>(welch.used) * welch.window_power;
    result.joints.resize(torques.size());
    for_each_joint(torques.size(), threads, [&](std::size_t j) {
        const std::vector<double>& tau = *torques[j];
        JointTorqueBandwidth& jt = result.joints[j];
        jt.name = joint_name(names, j);
        jt.moving = varies(tau);
        if (!jt.moving) return;
        std::vector<double> power = welch.power(tau);  // mean removed per segment: bin 0 is no bandwidth
        for (std::size_t k = 0; k < bins; ++k) power[k] /= interpolation[k];
        const double level = result.noise_known ? noise_std[j] * noise_std[j] * per_variance : band.level(power, nullptr);
        double total = 0.0, removed = 0.0, variance = 0.0;
        std::vector<double> clean(bins, 0.0);
        for (std::size_t k = 1; k < bins; ++k) clean[k] = power[k] - level;
        for (std::size_t k = 1; k <= top; ++k) {
            total += power[k];
            removed += std::min(level, power[k]);
            variance += std::max(clean[k], 0.0);
        }
        jt.floor_fraction = total > 0.0 ? removed / total : 0.0;
        jt.noise_rms = std::sqrt(level / per_variance);
        jt.frequency = energy_frequency(clean, result.resolution, fraction, result.highest);
        // Same rule as the positions': the torque's variance at least kMotionToNoise x its floor's.
        jt.used = variance >= kMotionToNoise * level * static_cast<double>(top);
    });
    // Each joint's own band counts (its equations are biased when the smoothing cuts its torque, whatever the
    // other joints hold): the widest of the joints used.
    for (const auto& jt : result.joints) {
        if (jt.used) result.frequency = std::max(result.frequency, jt.frequency);
    }
    return result;
}

double torque_highest(const BandwidthEstimate& motion, double cutoff_ratio) { return cutoff_ratio * motion.noise_limit; }

BandwidthEstimate with_torque(BandwidthEstimate motion, TorqueBandwidth torque, double cutoff_ratio) {
    motion.torque = std::move(torque);
    if (!motion.moving) return motion;
    const double wanted = std::max(motion.energy_frequency, motion.torque.frequency);
    motion.torque_wider = motion.torque.frequency > motion.energy_frequency;
    motion.torque_noise_limited = motion.torque_wider && motion.noise_limit < motion.torque.frequency;
    motion.differentiator_frequency = std::min(wanted, motion.noise_limit);
    motion.description = describe_bandwidth(motion, cutoff_ratio);
    return motion;
}

BandwidthEstimate estimate_bandwidth(const std::vector<const std::vector<double>*>& positions, const std::vector<const std::vector<double>*>& torques,
                                     double sample_period, const std::vector<std::string>& position_names,
                                     const std::vector<std::string>& torque_names, double cutoff_ratio, double fraction, int threads,
                                     double torque_shift) {
    BandwidthEstimate motion = estimate_motion_bandwidth(positions, sample_period, position_names, cutoff_ratio, fraction, threads);
    if (!motion.moving) return motion;
    TorqueBandwidth torque = estimate_torque_bandwidth(torques, sample_period, torque_names, torque_highest(motion, cutoff_ratio), fraction,
                                                       threads, {}, torque_shift);
    return with_torque(std::move(motion), std::move(torque), cutoff_ratio);
}

}  // namespace jacobid::identify
