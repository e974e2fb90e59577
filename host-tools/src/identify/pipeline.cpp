// SPDX-License-Identifier: MIT
#include "identify/pipeline.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <exception>
#include <functional>
#include <map>
#include <cmath>
#include <utility>

#include "core/errors.hpp"
#include "core/free_memory.hpp"
#include "core/huge_pages.hpp"
#include "core/parallel_for.hpp"
#include "identify/bandwidth.hpp"
#include "identify/running_qr.hpp"
#include "identify/state_source.hpp"
#include "identify/torque_smoothing.hpp"
#include "jacobid/baseline/butterworth.hpp"
#include "jacobid/baseline/euler_difference.hpp"
#include "jacobid/baseline/filtfilt.hpp"
#include "jacobid/frequency_response.hpp"
#include "jacobid/kernel_design.hpp"
#include "signal/baseline_response.hpp"
#include "signal/fft_convolver.hpp"
#include "signal/interleaved_filtfilt.hpp"

namespace jacobid::identify {
namespace {
using Clock = std::chrono::steady_clock;
using Lowpass = signal::ButterworthSos;  // Butterworth up to order 16

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

KernelParams jacobi_params(const PipelineSettings& s, int order, double ts) {
    KernelParams p;
    p.order = order;
    p.kappa = s.kappa;
    p.mu = s.mu;
    p.q = s.q;
    p.sample_period = ts;
    p.discretization = s.exact_discretization ? Discretization::Exact : Discretization::Trapezoidal;
    p.xi = 0.0;  // central: delay-free once aligned, as the off-line identification wants
    return p;
}

std::size_t odd_taps_for_window(double window, double ts) {
    std::size_t taps = static_cast<std::size_t>(std::llround(window / ts)) + 1;
    if (taps % 2 == 0) ++taps;
    return taps;
}

std::vector<double> design_or_throw(KernelParams p) {
    std::vector<double> w(tap_count(p));
    const KernelStatus status = design_kernel(p, Span<double>(w));
    if (status != KernelStatus::Ok) throw InputError(fmt::format("Jacobi order-{} differentiator: {}", p.order, describe(status)));
    return w;
}

void filtfilt_or_throw(const Lowpass& sos, const double* x, double* y, std::size_t n, std::vector<double>& workspace) {
    workspace.resize(sosfiltfilt_workspace_size(sos));
    const FilterStatus status = sosfiltfilt(sos, Span<const double>(x, n), Span<double>(y, n), Span<double>(workspace));
    if (status != FilterStatus::Ok) throw InputError(fmt::format("zero-phase filter on {} samples: {}", n, describe(status)));
}

// A Jacobi velocity kernel (the pipeline's kappa, mu, q) whose cutoff is closest to `cutoff`.
std::vector<double> coulomb_velocity_kernel(const PipelineSettings& s, double ts, std::size_t n, double cutoff) {
    std::vector<double> scratch(std::max<std::size_t>(std::min<std::size_t>(n, 2'000'001), 3));
    KernelParams p = jacobi_params(s, 1, ts);
    const WindowDesign d = window_for_cutoff(p, cutoff, true, Span<double>(scratch));
    if (d.status != KernelStatus::Ok) throw InputError(fmt::format("Coulomb velocity window design: {}", describe(d.status)));
    p.window = d.window;
    return design_or_throw(p);
}

// s'_j(0): the slope at qd = 0 of joint j's Coulomb column s(alpha qd); 0 when the model has no FCj column or
// its sign is not smooth (s jumps to about 1 already at qd = 1e-7).
double coulomb_slope(const robot::RobotModel& model, int joint) {
    const int index = model.parameter_index(fmt::format("FC{}", joint + 1));
    if (index < 0) return 0.0;
    const int joints = model.joint_count();
    std::vector<double> q(static_cast<std::size_t>(joints), 0.0), qd(q), qdd(q);
    constexpr double eps = 1e-7;
    qd[static_cast<std::size_t>(joint)] = eps;
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(joints, model.parameter_count());
    model.regressor(q.data(), qd.data(), qdd.data(), D);
    const double value = D(joint, index);
    return std::isfinite(value) && value > 0.0 && value < 0.5 ? value / eps : 0.0;
}

// The Coulomb velocity's cutoff ratio per joint (PipelineSettings::coulomb_velocity_ratio). A given ratio
// applies to every joint. Auto (< 0): the wider of 2, 1.5 x the cutoff whose position noise in
// the sign function, s'_j(0) sigma_q,j ||w||_2 (w: that velocity estimate's weights, `noise_gain`), stays
// within kCoulombVelocityNoise (of the sign's transition width); 1 otherwise, or when s'_j(0) or the model
// is unknown. sigma_q,j is the bandwidth estimate's white position noise. Not wider than 2: on issue 14's
// experiment 2.5 and 3 left the ZZ2 bias where 2 had it and added the noise bias (docs/method.md).
std::vector<double> automatic_coulomb_ratios(const robot::RobotModel* model, const LogColumns& log, const PipelineSettings& s,
                                             const PipelineInfo& info, const std::function<double(double)>& noise_gain) {
    const std::size_t joints = log.q.size();
    std::vector<double> ratios(joints, 1.0);
    if (!model || model->joint_count() != static_cast<int>(joints)) return ratios;
    const BandwidthEstimate estimate =
        info.bandwidth_estimated ? info.bandwidth_estimate : estimate_motion_bandwidth(log.q, log.sample_period, log.q_names, s.differentiator_ratio, kMotionEnergyFraction, s.threads);
    std::vector<std::pair<double, double>> gains;  // ratio, ||w||_2
    for (double candidate : {2.0, 1.5}) gains.emplace_back(candidate, noise_gain(candidate));
    for (std::size_t j = 0; j < joints; ++j) {
        const double alpha = coulomb_slope(*model, static_cast<int>(j));
        if (alpha <= 0.0 || j >= estimate.joints.size()) continue;
        const double sigma_q = estimate.joints[j].noise_rms;
        for (const auto& [candidate, gain] : gains) {
            if (alpha * sigma_q * gain <= kCoulombVelocityNoise) {
                ratios[j] = candidate;
                break;
            }
        }
    }
    return ratios;
}

// The Coulomb columns' velocity cutoff at `ratio` x the pipeline's (the differentiators' or F_q's), below 0.4 fs.
double coulomb_cutoff(const PipelineSettings& s, const PipelineInfo& info, double ts, double ratio) {
    return std::min(ratio * (s.method == Method::Jacobi ? info.differentiator_cutoff : info.prefilter_cutoff), 0.4 / ts);
}

// White-noise gain ||w||_2 of the Coulomb velocity estimate at `ratio`: the Jacobi kernel's weights, or the
// impulse response of the forward-backward Butterworth followed by the central difference.
double coulomb_noise_gain(const PipelineSettings& s, const PipelineInfo& info, double ts, std::size_t n, double ratio) {
    const double cutoff = coulomb_cutoff(s, info, ts, ratio);
    double sum = 0.0;
    if (s.method == Method::Jacobi) {
        for (double w : coulomb_velocity_kernel(s, ts, n, cutoff)) sum += w * w;
        return std::sqrt(sum);
    }
    const Lowpass f = signal::design_butterworth_or_throw(s.butterworth_order, cutoff, ts, "Coulomb velocity prefilter");
    const std::size_t half = static_cast<std::size_t>(std::ceil(20.0 / (cutoff * ts))) + 2;
    std::vector<double> x(2 * half + 1, 0.0), y(x.size()), d(x.size());
    x[half] = 1.0;
    std::vector<double> w;
    filtfilt_or_throw(f, x.data(), y.data(), x.size(), w);
    euler_first_derivative(Span<const double>(y), ts, Span<double>(d));
    for (std::size_t k = 1; k + 1 < d.size(); ++k) sum += d[k] * d[k];
    return std::sqrt(sum);
}

// The Jacobi kernels of a planned log (windows in `info`), and the cutoffs they achieve into `info`:
// velocity, acceleration, the torque smoothing (the velocity kernel's low-pass: torque_smoothing.hpp, so that
// Y and the regressor see the same filter in F_p's band), and per joint the Coulomb columns' velocity at
// `ratios` x the cutoff (empty ratios: off).
JacobiKernels design_jacobi_kernels(const LogColumns& log, const PipelineSettings& s, PipelineInfo& info, const std::vector<double>& ratios) {
    const double ts = log.sample_period;
    const std::size_t n = log.samples();
    JacobiKernels k;
    KernelParams pv = jacobi_params(s, 1, ts), pa = jacobi_params(s, 2, ts);
    pv.window = info.velocity_window;
    pa.window = info.acceleration_window;
    k.velocity = design_or_throw(pv);
    k.acceleration = design_or_throw(pa);
    info.velocity_cutoff = find_cutoff(Span<const double>(k.velocity), ts, 1).frequency;
    info.acceleration_cutoff = find_cutoff(Span<const double>(k.acceleration), ts, 2).frequency;
    k.torque = torque_smoothing_kernel(k.velocity, ts);
    if (ratios.empty()) return k;
    const std::size_t joints = log.q.size();
    info.coulomb_velocity_cutoffs.assign(joints, 0.0);
    std::map<double, std::vector<double>> designs;  // one design per distinct ratio (joints usually share one)
    for (std::size_t j = 0; j < joints; ++j) {
        auto [it, designed] = designs.try_emplace(ratios[j]);
        if (designed) it->second = coulomb_velocity_kernel(s, ts, n, coulomb_cutoff(s, info, ts, ratios[j]));
        const std::vector<double>& wc = it->second;
        if (wc.size() > n) throw InputError(fmt::format("{}: {} samples are shorter than the Coulomb velocity kernel", log.source, n));
        info.coulomb_velocity_cutoffs[j] = find_cutoff(Span<const double>(wc), ts, 1).frequency;
        k.coulomb.push_back(wc);
    }
    return k;
}

}  // namespace

std::vector<double> coulomb_velocity_ratios(const robot::RobotModel* model, const LogColumns& log, const PipelineSettings& s,
                                            const PipelineInfo& info) {
    const std::size_t joints = log.q.size();
    if (s.measured_velocity || s.coulomb_velocity_ratio == 0.0) return {};
    if (!s.coulomb_velocity_ratios.empty()) {
        if (s.coulomb_velocity_ratios.size() != joints) {
            throw InputError(fmt::format("{}: {} Coulomb velocity ratios imposed on {} joints", log.source, s.coulomb_velocity_ratios.size(), joints));
        }
        return s.coulomb_velocity_ratios;
    }
    if (s.coulomb_velocity_ratio > 0.0) return std::vector<double>(joints, s.coulomb_velocity_ratio);
    return automatic_coulomb_ratios(model, log, s, info,
                                    [&](double ratio) { return coulomb_noise_gain(s, info, log.sample_period, log.samples(), ratio); });
}

const char* to_string(Method m) { return m == Method::Jacobi ? "jacobi" : "butterworth"; }

void RowSink::filtered_torque(std::size_t, std::size_t, const std::vector<const double*>&) {}

PipelineInfo plan_pipeline(const LogColumns& log, const PipelineSettings& s) {
    PipelineInfo info;
    info.method = s.method;
    info.sample_period = log.sample_period;
    info.samples = log.samples();
    const double ts = log.sample_period;
    const double fs = 1.0 / ts;
    const std::size_t n = info.samples;
    for (const auto* q : log.q) {
        const auto [lo, hi] = std::minmax_element(q->begin(), q->end());
        info.joint_range.push_back(n ? *hi - *lo : 0.0);
        info.joint_moves.push_back(n && *hi - *lo > s.min_joint_motion);
    }
    if (std::none_of(info.joint_moves.begin(), info.joint_moves.end(), [](bool b) { return b; })) {
        throw InputError(fmt::format("{}: the robot stands still (every joint's position range is below {} rad): no parameter can be identified",
                                     log.source, s.min_joint_motion));
    }
    std::string bandwidth_description;  // what the automatic estimate saw, for the errors below
    if (s.bandwidth > 0.0) {
        info.bandwidth = s.bandwidth;
    } else {
        // The motion's bandwidth, and the differentiators' widened to the torque's band (bandwidth.hpp): they
        // and the torque's smoothing must pass both alike. Torques aligned by a torque delay are read through
        // its interpolation.
        const BandwidthEstimate b =
            estimate_bandwidth(log.q, log.tau, ts, log.q_names, log.tau_names, s.differentiator_ratio, kMotionEnergyFraction, s.threads,
                               log.tau_aligned_by / ts);
        if (!b.moving) throw InputError(fmt::format("{}: the positions are constant: no parameter can be identified", log.source));
        info.bandwidth = b.frequency;
        info.bandwidth_estimated = true;
        bandwidth_description = b.description;
        info.bandwidth_estimate = b;
    }
    // Estimated: the differentiators (and the torque's smoothing) pass the torque's band too (bandwidth.hpp).
    const double differentiator_bandwidth = info.bandwidth_estimated ? info.bandwidth_estimate.differentiator_frequency : info.bandwidth;
    info.differentiator_cutoff = s.differentiator_cutoff > 0.0 ? s.differentiator_cutoff : s.differentiator_ratio * differentiator_bandwidth;
    info.differentiator_cutoff = std::min(info.differentiator_cutoff, 0.4 * fs);
    if (s.method == Method::Jacobi) {
        // Windows: explicit, or the odd tap count whose cutoff is closest to the wanted one.
        const std::size_t max_taps = std::max<std::size_t>(std::min<std::size_t>(n, 2'000'001), 3);
        std::vector<double> scratch(max_taps);
        auto window_for = [&](int order, double explicit_window) {
            if (explicit_window > 0.0) return static_cast<double>(odd_taps_for_window(explicit_window, ts) - 1) * ts;
            const WindowDesign d = window_for_cutoff(jacobi_params(s, order, ts), info.differentiator_cutoff, true, Span<double>(scratch));
            if (d.status == KernelStatus::TooManyTaps) {
                throw InputError(fmt::format("{}: {} samples are too short for the Jacobi window of a {:.3g} Hz cutoff (bandwidth {:.3g} Hz); "
                                             "give --cutoff or --velocity-window/--acceleration-window",
                                             log.source, n, info.differentiator_cutoff, info.bandwidth));
            }
            if (d.status != KernelStatus::Ok) throw InputError(fmt::format("Jacobi window design: {}", describe(d.status)));
            return d.window;
        };
        info.velocity_window = window_for(1, s.velocity_window);
        info.acceleration_window = window_for(2, s.acceleration_window);
        const std::size_t h = (std::max(odd_taps_for_window(info.velocity_window, ts), odd_taps_for_window(info.acceleration_window, ts)) - 1) / 2;
        if (2 * h + 1 > n) {
            throw InputError(fmt::format("{}: {} samples are shorter than the differentiator window ({} samples = {:.4g} s)", log.source, n,
                                         2 * h + 1, static_cast<double>(2 * h) * ts));
        }
        info.first = h;
        info.last = n - h;
    } else {
        if (info.differentiator_cutoff >= 0.5 * fs) {
            throw InputError(fmt::format("--cutoff {:.4g} Hz must be below half the sample rate ({:.4g} Hz)", info.differentiator_cutoff, 0.5 * fs));
        }
        info.prefilter_cutoff = info.differentiator_cutoff;
        const auto edge = static_cast<std::size_t>(std::ceil(3.0 * fs / info.prefilter_cutoff)) + 1;
        if (2 * edge + 3 > n) {
            throw InputError(fmt::format("{}: {} samples are too short for the Butterworth prefilter's end transients ({} samples each)",
                                         log.source, n, edge));
        }
        info.first = edge;
        info.last = n - edge;
    }
    info.decimation_cutoff = s.decimation_cutoff > 0.0 ? s.decimation_cutoff : s.decimation_ratio * info.bandwidth;
    if (info.decimation_cutoff >= 0.5 * fs && info.bandwidth_estimated && s.decimation_cutoff <= 0.0) {
        throw InputError(fmt::format("{}: the estimated motion bandwidth, {}, puts the decimation filter ({} x bandwidth = {:.4g} Hz) above "
                                     "half the sample rate ({:.4g} Hz); give --bandwidth (the motion's bandwidth in Hz)",
                                     log.source, bandwidth_description, s.decimation_ratio, info.decimation_cutoff, 0.5 * fs));
    }
    if (info.decimation_cutoff >= 0.5 * fs && s.decimation_cutoff <= 0.0) {
        // The cutoff follows from the --bandwidth given: name that option, not one the user never gave.
        throw InputError(fmt::format("--bandwidth {:.4g} Hz puts the decimation filter ({} x bandwidth = {:.4g} Hz) above half the sample rate "
                                     "({:.4g} Hz); give a --bandwidth below {:.4g} Hz",
                                     info.bandwidth, s.decimation_ratio, info.decimation_cutoff, 0.5 * fs, 0.5 * fs / s.decimation_ratio));
    }
    if (info.decimation_cutoff >= 0.5 * fs) {
        throw InputError(fmt::format("--decimation-cutoff {:.4g} Hz must be below half the sample rate ({:.4g} Hz)", info.decimation_cutoff, 0.5 * fs));
    }
    info.decimation = s.decimation > 0 ? s.decimation : std::max(1, static_cast<int>(std::floor(fs / (4.0 * info.decimation_cutoff))));
    info.crop = static_cast<std::size_t>(std::ceil(3.0 * fs / info.decimation_cutoff));
    if (info.last <= info.first + 2 * info.crop + 1) {
        throw InputError(fmt::format("{}: {} samples are too short: the differentiator windows and the decimation filter's end transients "
                                     "({} + 2 x {} samples) leave nothing to identify",
                                     log.source, n, info.first * 2, info.crop));
    }
    return info;
}

StateEstimates estimate_states(const LogColumns& log, const PipelineSettings& s, PipelineInfo& info, const robot::RobotModel* model) {
    const auto start = Clock::now();
    const std::size_t n = log.samples();
    const std::size_t joints = log.q.size();
    const double ts = log.sample_period;
    StateEstimates e;
    e.first = info.first;
    e.last = info.last;
    e.q.resize(joints);
    e.qd.assign(joints, std::vector<double>(n, 0.0));
    e.qdd.assign(joints, std::vector<double>(n, 0.0));
    e.tau.resize(joints);
    std::vector<double> smoothing;  // Jacobi: the velocity kernel's low-pass, for a measured velocity
    // The Coulomb columns' velocity per joint (empty: off), chosen before the estimates so that an imposed
    // plan (validation, segments, several logs) carries it.
    const std::vector<double> ratios = coulomb_velocity_ratios(model, log, s, info);
    info.coulomb_velocity_ratios = ratios;
    info.coulomb_velocity_cutoffs.clear();
    if (s.method == Method::Jacobi) {
        JacobiKernels kernels = design_jacobi_kernels(log, s, info, ratios);
        if (s.measured_velocity) smoothing = kernels.torque;
        for (std::size_t j = 0; j < joints; ++j) {
            centered_fir_range(kernels.velocity, *log.q[j], 0, e.qd[j], 0.0, 0.0, log.source);
            centered_fir_range(kernels.acceleration, *log.q[j], 0, e.qdd[j], 0.0, 0.0, log.source);
            e.q[j] = *log.q[j];
            e.tau[j].assign(n, 0.0);
            centered_fir_range(kernels.torque, *log.tau[j], 0, e.tau[j], 0.0, 0.0, log.source);
        }
        if (!ratios.empty()) {
            e.torque_fir = kernels.torque;
            e.qd_coulomb.assign(joints, std::vector<double>(n, 0.0));
            for (std::size_t j = 0; j < joints; ++j) {
                // Held at the first and last outputs beyond them.
                const std::size_t hc = (kernels.coulomb[j].size() - 1) / 2;
                auto& v = e.qd_coulomb[j];
                centered_fir_range(kernels.coulomb[j], *log.q[j], 0, v, 0.0, 0.0, log.source);
                std::fill(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(hc), v[hc]);
                std::fill(v.end() - static_cast<std::ptrdiff_t>(hc), v.end(), v[n - hc - 1]);
            }
        }
    } else {
        // The paper's baseline: positions AND torques through the same forward-backward Butterworth F_q
        // (filtering only q would leave torque content the regressor lacks), then central Euler differences.
        const Lowpass fq = signal::design_butterworth_or_throw(s.butterworth_order, info.prefilter_cutoff, ts, "Butterworth prefilter");
        std::vector<double> workspace;
        for (std::size_t j = 0; j < joints; ++j) {
            e.q[j].resize(n);
            e.tau[j].resize(n);
            filtfilt_or_throw(fq, log.q[j]->data(), e.q[j].data(), n, workspace);
            filtfilt_or_throw(fq, log.tau[j]->data(), e.tau[j].data(), n, workspace);
            euler_first_derivative(Span<const double>(e.q[j]), ts, Span<double>(e.qd[j]));
            euler_second_derivative(Span<const double>(e.q[j]), ts, Span<double>(e.qdd[j]));
        }
        if (!ratios.empty()) {
            // The Coulomb columns' velocity: central differences of the positions through a Butterworth of
            // the same order at the joint's ratio x F_q's cutoff (the columns then go through F_q like the torque).
            e.qd_coulomb.assign(joints, std::vector<double>(n, 0.0));
            info.coulomb_velocity_cutoffs.assign(joints, 0.0);
            std::vector<double> qf(n);
            for (std::size_t j = 0; j < joints; ++j) {
                const double cutoff = coulomb_cutoff(s, info, ts, ratios[j]);
                const Lowpass fc = signal::design_butterworth_or_throw(s.butterworth_order, cutoff, ts, "Coulomb velocity prefilter");
                info.coulomb_velocity_cutoffs[j] = cutoff;
                filtfilt_or_throw(fc, log.q[j]->data(), qf.data(), n, workspace);
                euler_first_derivative(Span<const double>(qf), ts, Span<double>(e.qd_coulomb[j]));
            }
        }
    }
    if (s.measured_velocity) {
        // The drive's own velocity (often from a finer encoder or an observer) replaces the differentiated
        // one, through the filter the torque went through: the same F_q in the Butterworth baseline, the
        // velocity kernel's low-pass in the Jacobi method (otherwise FV and FC would see the filter mismatch
        // that the torque smoothing removes).
        const Lowpass fq = s.method == Method::Butterworth
                               ? signal::design_butterworth_or_throw(s.butterworth_order, info.prefilter_cutoff, ts, "Butterworth prefilter")
                               : Lowpass{};
        std::vector<double> workspace;
        for (std::size_t j = 0; j < joints; ++j) {
            const auto* measured = j < log.qd.size() ? log.qd[j] : nullptr;
            if (!measured) {
                throw InputError(fmt::format("--velocity measured: {} has no measured velocity for joint {} (a column qd{}, or velocities: in --log-format)",
                                             log.source, j + 1, j + 1));
            }
            if (measured->size() != n) {
                throw InputError(fmt::format("--velocity measured: {}: velocity column qd{} has {} samples, the positions {}", log.source, j + 1,
                                             measured->size(), n));
            }
            if (s.method == Method::Butterworth) {
                filtfilt_or_throw(fq, measured->data(), e.qd[j].data(), n, workspace);
                continue;
            }
            std::vector<double> out(n - smoothing.size() + 1);
            const BatchStatus status = signal::differentiate_batch(Span<const double>(smoothing), Span<const double>(*measured),
                                                                   Span<double>(out.data(), out.size()));
            if (status != BatchStatus::Ok) throw InputError(fmt::format("{}: {}", log.source, describe(status)));
            std::fill(e.qd[j].begin(), e.qd[j].end(), 0.0);
            std::copy(out.begin(), out.end(), e.qd[j].begin() + static_cast<std::ptrdiff_t>((smoothing.size() - 1) / 2));
        }
    }
    // A joint below the motion threshold is standing still: what its estimates contain is encoder
    // flicker and servo jitter, not excitation. Pinning it (mean position, zero velocity and acceleration)
    // makes the parameters only its motion excites exactly unidentifiable (zero columns, null
    // combinations), which the LS then reports, instead of fitting them to noise.
    for (std::size_t j = 0; j < joints && j < info.joint_moves.size(); ++j) {
        if (info.joint_moves[j]) continue;
        double mean = 0.0;
        for (std::size_t k = e.first; k < e.last; ++k) mean += e.q[j][k];
        mean /= static_cast<double>(e.last - e.first);
        std::fill(e.q[j].begin(), e.q[j].end(), mean);
        std::fill(e.qd[j].begin(), e.qd[j].end(), 0.0);
        std::fill(e.qdd[j].begin(), e.qdd[j].end(), 0.0);
    }
    info.seconds_differentiate = seconds_since(start);
    return e;
}

namespace {
// Steps 2-4 (regressor, F_p, decimation, factors) on the estimates `states` gives chunk by chunk.
PipelineOutput fold_source(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& s, PipelineInfo planned,
                           const StateSource& states, RowSink* sink);
}  // namespace

PipelineOutput run_pipeline(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& s, RowSink* sink) {
    PipelineInfo info = plan_pipeline(log, s);
    if (s.progress) {
        fmt::print(stderr, "identify [{}]: {} samples, bandwidth {:.3g} Hz{}, F_p {:.3g} Hz, decimation {}\n", to_string(s.method),
                   log.samples(), info.bandwidth, info.bandwidth_estimated ? " (estimated)" : "", info.decimation_cutoff, info.decimation);
    }
    if (s.method == Method::Jacobi && !s.measured_velocity) {
        // The estimates are computed chunk by chunk as the fold asks for them (state_source.hpp), from the
        // log's own columns: no full-length estimate is held (an hour of 6-axis data held 0.86 GB of them).
        const auto start = Clock::now();
        const std::vector<double> ratios = coulomb_velocity_ratios(&model, log, s, info);
        info.coulomb_velocity_ratios = ratios;
        info.coulomb_velocity_cutoffs.clear();
        const StreamedJacobiStates states(log, design_jacobi_kernels(log, s, info, ratios), info.joint_moves, info.first, info.last);
        info.seconds_differentiate = seconds_since(start);
        if (s.progress) fmt::print(stderr, "identify [{}]: kernels in {:.2f} s, derivatives computed chunk by chunk\n", to_string(s.method), info.seconds_differentiate);
        return fold_source(model, log, s, std::move(info), states, sink);
    }
    const StateEstimates e = estimate_states(log, s, info, &model);
    if (s.progress) fmt::print(stderr, "identify [{}]: derivatives in {:.2f} s\n", to_string(s.method), info.seconds_differentiate);
    return fold_states(model, log, s, std::move(info), e, sink);
}

PipelineOutput fold_states(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& s, PipelineInfo planned,
                           const StateEstimates& e, RowSink* sink) {
    return fold_source(model, log, s, std::move(planned), HeldStates(e), sink);
}

namespace {

// One chunk's columns (every joint's regressor columns and torque) in one block, `stride` samples apart:
// 318 vectors of 0.3 MB for a 6-axis robot were each a separate mapping that glibc returned to the kernel
// at the end of every identification, so every run faulted its 90 MB in again 4 KB at a time; one block
// is reused by every chunk and can be backed by huge pages (core/huge_pages.hpp).
// Only the columns that have held a nonzero value get a slot in the block: a serial robot's joint j row is
// zero for the parameters of the links before j and for the other joints' friction, about half of the
// PUMA 560's 318 columns (93 MB of an hour's 140 MB plateau above the log). A column without a slot reads
// as zeros, which is what the regressor wrote into it before.
class ChunkColumns {
public:
    static constexpr std::size_t kNoSlot = static_cast<std::size_t>(-1);
    explicit ChunkColumns(std::size_t columns) : slot_(columns, kNoSlot) {}
    // Gives `column` a slot; the block must be fitted again before the next write (its contents are lost).
    void add(std::size_t column) {
        if (slot_[column] == kNoSlot) slot_[column] = slots_++;
    }
    bool has(std::size_t column) const { return slot_[column] != kNoSlot; }
    // Room for `samples` per slotted column; the contents are not kept (every chunk writes its columns whole).
    void fit(std::size_t samples) {
        if (samples <= stride_ && slots_ == fitted_slots_) return;
        stride_ = std::max(stride_, samples);
        fitted_slots_ = slots_;
        storage_ = std::vector<double>();
        storage_.reserve(slots_ * stride_);
        advise_huge_pages(storage_);  // before the first write, which faults the pages in
        storage_.resize(slots_ * stride_);
    }
    // The column's samples, nullptr without a slot.
    double* operator[](std::size_t column) { return has(column) ? storage_.data() + slot_[column] * stride_ : nullptr; }
    // Sample i of the column (0 without a slot).
    double at(std::size_t column, std::size_t i) const { return has(column) ? storage_[slot_[column] * stride_ + i] : 0.0; }

private:
    std::vector<std::size_t> slot_;  // per column
    std::size_t slots_ = 0, fitted_slots_ = 0, stride_ = 0;
    std::vector<double> storage_;
};

PipelineOutput fold_source(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& s, PipelineInfo planned,
                           const StateSource& states, RowSink* sink) {
    PipelineOutput out;
    out.info = std::move(planned);
    PipelineInfo& info = out.info;
    // Columns with memory (presliding friction): their state integrated once along the whole log's raw
    // positions, then written into every row before F_p, so they are filtered and decimated like the rest.
    const auto history_size = static_cast<std::size_t>(model.history_size());
    std::vector<double> history;
    model.integrate_history(log.q, history);

    const int joints = model.joint_count();
    const int c = model.parameter_count();
    const double fs = 1.0 / log.sample_period;
    const Lowpass fp = signal::design_butterworth_or_throw(s.decimation_order, info.decimation_cutoff, log.sample_period, "decimation filter F_p");
    // Margin: F_p's impulse response decays as exp(-0.38 * 2 pi fc t) for order 4 (slowest pole); 16 / fc
    // seconds bring a chunk boundary's transient below 1e-16 whatever the order up to 16.
    const auto margin = static_cast<std::size_t>(std::ceil(16.0 * fs / info.decimation_cutoff * std::max(1.0, s.decimation_order / 4.0)));
    const std::size_t a0 = info.first, a1 = info.last;
    std::size_t keep0 = a0 + info.crop, keep1 = a1 - info.crop;
    if (s.kept_to > s.kept_from) {
        if (s.kept_from < keep0 || s.kept_to > keep1) {
            throw InputError(fmt::format("{}: the samples to keep [{}, {}) reach into the differentiator and F_p transients (valid [{}, {}))",
                                         log.source, s.kept_from, s.kept_to, keep0, keep1));
        }
        keep0 = s.kept_from;
        keep1 = s.kept_to;
    }
    const std::size_t d = static_cast<std::size_t>(info.decimation);
    const std::size_t chunk = std::max(s.chunk, 4 * margin);

    std::vector<RunningQr> qr;
    std::vector<LaggedProducts> lagged;  // residual autocorrelation, for the std (residual_correlation.hpp)
    for (int j = 0; j < joints; ++j) {
        qr.emplace_back(c + 1);
        lagged.emplace_back(c + 1, s.residual_lags);
    }
    const std::size_t columns = static_cast<std::size_t>(joints) * static_cast<std::size_t>(c + 1);
    return_freed_memory();  // the set-up's whole-log temporaries, before the fold's own buffers
    ChunkColumns buffer(columns);
    for (int j = 0; j < joints; ++j) buffer.add(static_cast<std::size_t>(j) * static_cast<std::size_t>(c + 1) + static_cast<std::size_t>(c));
    // The columns that hold a value at a few arbitrary states get their slots now, so that the first chunk
    // is not written twice (a short log is one or two chunks); a column found later gets its slot then.
    {
        Eigen::MatrixXd D(joints, c);
        std::vector<double> qs(static_cast<std::size_t>(joints)), qds(qs), qdds(qs), state(history_size, 0.5);
        for (int probe = 0; probe < 3; ++probe) {
            for (int j = 0; j < joints; ++j) {
                qs[static_cast<std::size_t>(j)] = 0.37 + 1.13 * probe + 0.71 * j;
                qds[static_cast<std::size_t>(j)] = 0.9 - 0.53 * probe + 0.29 * j;
                qdds[static_cast<std::size_t>(j)] = -1.7 + 0.83 * probe + 0.47 * j;
            }
            model.regressor(qs.data(), qds.data(), qdds.data(), D);
            if (history_size > 0) model.history_columns(state.data(), D);
            for (int j = 0; j < joints; ++j) {
                for (int p = 0; p < c; ++p) {
                    if (D(j, p) != 0.0) buffer.add(static_cast<std::size_t>(j) * static_cast<std::size_t>(c + 1) + static_cast<std::size_t>(p));
                }
            }
        }
    }
    // Work split over threads (settings.threads) in three stages per chunk: the regressor by sample ranges,
    // F_p by columns, the running QR by joints. Each piece of arithmetic is the same whatever the thread
    // count (no sum is split), so the result is identical bit for bit.
    const int threads = std::max(1, s.threads);
    ParallelForOptions pool;
    pool.threads = threads;
    std::vector<std::vector<double>> workspaces(static_cast<std::size_t>(threads));
    std::vector<signal::InterleavedFiltfilt> lane_filters(static_cast<std::size_t>(threads), signal::InterleavedFiltfilt(fp));
    std::vector<char> column_used(columns);
    // Per regressor range: the columns without a slot that it found nonzero (ChunkColumns).
    std::vector<std::vector<char>> unslotted_nonzero(static_cast<std::size_t>(threads), std::vector<char>(columns, 0));
    std::vector<std::size_t> used_columns;
    auto run_or_rethrow = [&](std::size_t jobs, const std::function<void(std::size_t)>& job) {
        for (const auto& error : parallel_for(jobs, pool, job)) {
            if (error) std::rethrow_exception(error);
        }
    };
    // The estimates of the chunk's samples (and of the Coulomb filter's reach around them).
    StateWindow window;
    // One sample's state for a regressor call, with the velocity from `qd` (window.qd, or the Coulomb columns' own).
    auto load_state = [&](std::size_t k, const std::vector<std::vector<double>>& qd, std::vector<double>& qs, std::vector<double>& qds,
                          std::vector<double>& qdds) {
        const std::size_t i = k - window.from;
        for (std::size_t j = 0; j < qs.size(); ++j) {
            qs[j] = window.q[j][i];
            qds[j] = qd[j][i];
            qdds[j] = window.qdd[j][i];
        }
    };
    std::vector<int> coulomb_columns;  // RobotModel::coulomb_column_indices, when their velocity is given (StateEstimates::qd_coulomb)
    std::vector<std::vector<double>> coulomb_raw;
    const std::size_t full_length = states.samples();
    const std::vector<double>& torque_fir = states.torque_fir();
    Lowpass coulomb_fq{};
    if (states.has_coulomb_velocity()) {
        coulomb_columns = model.coulomb_column_indices();
        coulomb_raw.resize(coulomb_columns.size() * static_cast<std::size_t>(joints));
        if (torque_fir.empty()) {
            coulomb_fq = signal::design_butterworth_or_throw(s.butterworth_order, info.prefilter_cutoff, log.sample_period, "Butterworth prefilter");
        }
    }
    std::vector<double> row(static_cast<std::size_t>(c + 1));
    out.plot.y.resize(static_cast<std::size_t>(joints));
    out.plot.w.resize(static_cast<std::size_t>(joints));
    DecimatedRow decimated;
    std::vector<const double*> torque_piece(static_cast<std::size_t>(joints));
    if (sink) {
        decimated.w.resize(joints, c);
        decimated.y.resize(joints);
        decimated.q.resize(joints);
        decimated.qd.resize(joints);
        decimated.qdd.resize(joints);
    }
    double regressor_seconds = 0.0, ls_seconds = 0.0;
    int reported_tenth = 0;
    struct SlottedEntry {
        std::size_t entry;  // in D's storage
        double* column;     // the chunk's samples of its column
    };
    struct UnslottedEntry {
        std::size_t entry, column;
    };
    std::vector<SlottedEntry> slotted;
    std::vector<UnslottedEntry> unslotted;
    // Decimated samples are k = a0 + m d; the first kept one is the first such k >= keep0.
    for (std::size_t c0 = keep0; c0 < keep1; c0 += chunk) {
        const std::size_t c1 = std::min(keep1, c0 + chunk);
        const std::size_t e0 = c0 >= a0 + margin ? c0 - margin : a0;
        const std::size_t e1 = std::min(a1, c1 + margin);
        const std::size_t len = e1 - e0;
        const auto t0 = Clock::now();
        // The Coulomb columns are filtered like the torque: their estimates reach `reach` samples further.
        const bool fir = !torque_fir.empty();
        const std::size_t reach = coulomb_columns.empty() ? 0 : fir ? (torque_fir.size() - 1) / 2 : info.first;
        const std::size_t x0 = e0 >= reach ? e0 - reach : 0, x1 = std::min(full_length, e1 + reach), xlen = x1 - x0;
        states.load(x0, x1, window, pool);
        const auto ranges = static_cast<std::size_t>(threads);
        const std::size_t regressor_ranges = model.concurrent_regressor() ? ranges : 1;
        // The chunk's columns are written again when one of them holds its first nonzero value (it then
        // gets a slot): rarely, the probe above has given most of them theirs.
        for (bool slots_added = true; slots_added;) {
            buffer.fit(len);
            // Where each entry of a sample's regressor D goes, worked out once per chunk rather than per entry
            // (6 x 52 branches per sample; without them, 5.4 % fewer instructions for a PUMA log, callgrind): the
            // columns with a slot are copied, the others only checked for a first nonzero value.
            slotted.clear();
            unslotted.clear();
            for (int j = 0; j < joints; ++j) {
                const std::size_t base = static_cast<std::size_t>(j) * static_cast<std::size_t>(c + 1);
                for (int p = 0; p < c; ++p) {
                    const std::size_t col = base + static_cast<std::size_t>(p);
                    const auto entry = static_cast<std::size_t>(p) * static_cast<std::size_t>(joints) + static_cast<std::size_t>(j);  // D is column-major
                    if (double* x = buffer[col]) {
                        slotted.push_back({entry, x});
                    } else {
                        unslotted.push_back({entry, col});
                    }
                }
            }
            run_or_rethrow(regressor_ranges, [&](std::size_t range) {
                Eigen::MatrixXd D(joints, c);
                std::vector<double> qs(static_cast<std::size_t>(joints)), qds(qs), qdds(qs);
                for (std::size_t i = len * range / regressor_ranges; i < len * (range + 1) / regressor_ranges; ++i) {
                    const std::size_t k = e0 + i;
                    load_state(k, window.qd, qs, qds, qdds);
                    model.regressor(qs.data(), qds.data(), qdds.data(), D);
                    if (history_size > 0) model.history_columns(history.data() + k * history_size, D);
                    const double* entries = D.data();
                    for (const SlottedEntry& e : slotted) e.column[i] = entries[e.entry];
                    for (const UnslottedEntry& e : unslotted) {
                        if (entries[e.entry] != 0.0) unslotted_nonzero[range][e.column] = 1;
                    }
                    for (int j = 0; j < joints; ++j) {
                        const std::size_t base = static_cast<std::size_t>(j) * static_cast<std::size_t>(c + 1);
                        buffer[base + static_cast<std::size_t>(c)][i] = window.tau[static_cast<std::size_t>(j)][k - window.from];
                    }
                }
            });
            if (!coulomb_columns.empty()) {
                // The Coulomb columns s(alpha qd) on the wider velocity, then through the torque's own filter
                // (StateEstimates::qd_coulomb), on [e0, e1) plus the filter's reach on each side.
                // Storage only where the column has a slot (a Coulomb column is zero outside its own joint's row);
                // a nonzero value elsewhere gives it one, as in the regressor above.
                const auto coulomb_column_of = [&](std::size_t ci, std::size_t j) {
                    return j * static_cast<std::size_t>(c + 1) + static_cast<std::size_t>(coulomb_columns[ci]);
                };
                for (std::size_t ci = 0; ci < coulomb_columns.size(); ++ci) {
                    for (std::size_t j = 0; j < static_cast<std::size_t>(joints); ++j) {
                        auto& raw = coulomb_raw[ci * static_cast<std::size_t>(joints) + j];
                        if (buffer.has(coulomb_column_of(ci, j))) {
                            raw.resize(xlen);
                        } else {
                            std::vector<double>().swap(raw);
                        }
                    }
                }
                // The Coulomb columns evaluated again per sample (RobotModel::coulomb_columns: alone for the serial
                // models, the whole regressor otherwise), split by sample ranges over the threads like the regressor.
                run_or_rethrow(regressor_ranges, [&](std::size_t range) {
                    Eigen::MatrixXd D(joints, c);
                    std::vector<double> qs(static_cast<std::size_t>(joints)), qds(qs), qdds(qs);
                    for (std::size_t k = x0 + xlen * range / regressor_ranges; k < x0 + xlen * (range + 1) / regressor_ranges; ++k) {
                        load_state(k, window.qd_coulomb, qs, qds, qdds);
                        model.coulomb_columns(qs.data(), qds.data(), qdds.data(), D);
                        for (std::size_t ci = 0; ci < coulomb_columns.size(); ++ci) {
                            for (int j = 0; j < joints; ++j) {
                                auto& raw = coulomb_raw[ci * static_cast<std::size_t>(joints) + static_cast<std::size_t>(j)];
                                const double value = D(j, coulomb_columns[ci]);
                                if (!raw.empty()) {
                                    raw[k - x0] = value;
                                } else if (value != 0.0) {
                                    unslotted_nonzero[range][coulomb_column_of(ci, static_cast<std::size_t>(j))] = 1;
                                }
                            }
                        }
                    }
                });
                std::vector<double> filtered(xlen);
                for (std::size_t ci = 0; ci < coulomb_columns.size(); ++ci) {
                    for (int j = 0; j < joints; ++j) {
                        const auto& raw = coulomb_raw[ci * static_cast<std::size_t>(joints) + static_cast<std::size_t>(j)];
                        double* target = buffer[coulomb_column_of(ci, static_cast<std::size_t>(j))];
                        // A filter of zeros is zeros (and a column without a slot has no raw values: it held none).
                        if (std::all_of(raw.begin(), raw.end(), [](double v) { return v == 0.0; })) {
                            if (target) std::fill(target, target + (e1 - e0), 0.0);
                            continue;
                        }
                        std::size_t shift = 0;  // filtered[m] belongs to sample x0 + m + shift
                        if (fir) {
                            const BatchStatus status = signal::differentiate_batch(Span<const double>(torque_fir), Span<const double>(raw),
                                                                                   Span<double>(filtered.data(), xlen - torque_fir.size() + 1));
                            if (status != BatchStatus::Ok) throw InputError(fmt::format("{}: {}", log.source, describe(status)));
                            shift = reach;
                        } else {
                            filtfilt_or_throw(coulomb_fq, raw.data(), filtered.data(), xlen, workspaces[0]);
                        }
                        for (std::size_t k = e0; k < e1; ++k) target[k - e0] = filtered[k - x0 - shift];
                    }
                }
            }
            slots_added = false;
            for (auto& found : unslotted_nonzero) {
                for (std::size_t col = 0; col < columns; ++col) {
                    if (!found[col]) continue;
                    found[col] = 0;
                    buffer.add(col);
                    slots_added = true;
                }
            }
        }
        // F_p on every column that holds anything (a column of zeros, e.g. a link's parameter in an earlier
        // joint's row, filters to zeros and stays as the regressor wrote it), kFiltfiltLanes columns at a
        // time (interleaved_filtfilt.hpp: each column's numbers are sosfiltfilt's, whatever its block).
        run_or_rethrow(ranges, [&](std::size_t t) {
            for (std::size_t col = t; col < columns; col += ranges) {
                const double* x = buffer[col];
                column_used[col] = x != nullptr && std::any_of(x, x + len, [](double v) { return v != 0.0; });
            }
        });
        used_columns.clear();
        for (std::size_t col = 0; col < columns; ++col) {
            if (column_used[col]) used_columns.push_back(col);
        }
        const std::size_t blocks = (used_columns.size() + signal::kFiltfiltLanes - 1) / signal::kFiltfiltLanes;
        run_or_rethrow(ranges, [&](std::size_t t) {
            std::array<double*, signal::kFiltfiltLanes> signals{};
            for (std::size_t b = t; b < blocks; b += ranges) {
                const std::size_t from = b * signal::kFiltfiltLanes;
                const std::size_t count = std::min(signal::kFiltfiltLanes, used_columns.size() - from);
                for (std::size_t l = 0; l < count; ++l) signals[l] = buffer[used_columns[from + l]];
                lane_filters[t].filter_in_place(signals.data(), count, len);
            }
        });
        const auto t1 = Clock::now();
        regressor_seconds += std::chrono::duration<double>(t1 - t0).count();
        if (sink) {
            // Each chunk hands out its kept samples [c0, c1); the first chunk also its leading margin and the
            // last its trailing one, which start at a0 and end at a1 (margin > crop), so the pieces tile
            // [a0, a1) once, every sample taken where its chunk's transients have died out.
            const std::size_t lo = c0 == keep0 ? e0 : c0, hi = c1 == keep1 ? e1 : c1;
            for (int j = 0; j < joints; ++j) {
                const std::size_t base = static_cast<std::size_t>(j) * static_cast<std::size_t>(c + 1);
                torque_piece[static_cast<std::size_t>(j)] = buffer[base + static_cast<std::size_t>(c)] + (lo - e0);
            }
            sink->filtered_torque(lo, hi - lo, torque_piece);
        }
        const std::size_t first_kept = c0 + (d - (c0 - a0) % d) % d;
        // Each joint's rows into its own running QR and lagged products (one joint per job, rows in order).
        run_or_rethrow(static_cast<std::size_t>(joints), [&](std::size_t j) {
            const std::size_t base = j * static_cast<std::size_t>(c + 1);
            std::vector<double> joint_row(static_cast<std::size_t>(c + 1));
            for (std::size_t k = first_kept; k < c1; k += d) {
                for (int p = 0; p <= c; ++p) joint_row[static_cast<std::size_t>(p)] = buffer.at(base + static_cast<std::size_t>(p), k - e0);
                qr[j].add_row(joint_row.data());
                lagged[j].add_row(joint_row.data());
            }
        });
        for (std::size_t k = first_kept; k < c1 && (sink || out.plot.t.size() < s.plot_rows); k += d) {
            const std::size_t i = k - e0;
            const bool keep_for_plot = out.plot.t.size() < s.plot_rows;
            const double t = log.start_time + static_cast<double>(k) * log.sample_period;
            if (keep_for_plot) out.plot.t.push_back(t);
            for (int j = 0; j < joints; ++j) {
                const std::size_t base = static_cast<std::size_t>(j) * static_cast<std::size_t>(c + 1);
                for (int p = 0; p <= c; ++p) row[static_cast<std::size_t>(p)] = buffer.at(base + static_cast<std::size_t>(p), i);
                if (keep_for_plot) {
                    out.plot.y[static_cast<std::size_t>(j)].push_back(row[static_cast<std::size_t>(c)]);
                    out.plot.w[static_cast<std::size_t>(j)].insert(out.plot.w[static_cast<std::size_t>(j)].end(), row.begin(), row.end() - 1);
                }
                if (sink) {
                    const auto js = static_cast<std::size_t>(j);
                    for (int p = 0; p < c; ++p) decimated.w(j, p) = row[static_cast<std::size_t>(p)];
                    decimated.y[j] = row[static_cast<std::size_t>(c)];
                    decimated.q[j] = window.q[js][k - window.from];
                    decimated.qd[j] = window.qd[js][k - window.from];
                    decimated.qdd[j] = window.qdd[js][k - window.from];
                }
            }
            if (sink) {
                decimated.sample = k;
                decimated.t = t;
                sink->row(decimated);
            }
        }
        ls_seconds += seconds_since(t1);
        if (s.progress && keep1 - keep0 > 10 * chunk) {
            // One line per tenth: readable in a terminal and in a CI log alike.
            const auto tenth = static_cast<int>(10 * (c1 - keep0) / (keep1 - keep0));
            if (tenth > reported_tenth) {
                reported_tenth = tenth;
                fmt::print(stderr, "identify [{}]: regressor + F_p {} %\n", to_string(s.method), 10 * tenth);
            }
        }
    }
    const auto t2 = Clock::now();
    for (auto& f : qr) {
        out.factors.r.push_back(f.r());
        out.factors.rows.push_back(f.rows());
    }
    if (s.residual_lags > 0) {
        for (auto& l : lagged) out.factors.lagged.push_back(l.gamma());
    }
    ls_seconds += seconds_since(t2);
    info.seconds_regressor_filter = regressor_seconds;
    info.seconds_ls = ls_seconds;
    std::size_t equations = 0;
    for (auto r : out.factors.rows) equations += r;
    if (s.require_own_equations && equations <= static_cast<std::size_t>(c)) {
        throw InputError(fmt::format("{}: only {} equations after decimation for {} parameters: the log is too short", log.source, equations, c));
    }
    if (s.progress) {
        fmt::print(stderr, "identify [{}]: regressor + F_p {:.2f} s, LS {:.2f} s, {} equations\n", to_string(s.method), regressor_seconds,
                   ls_seconds, equations);
    }
    return out;
}

}  // namespace

}  // namespace jacobid::identify
