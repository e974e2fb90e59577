// SPDX-License-Identifier: MIT
#include "identify/pipeline/pipeline.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <cmath>
#include <utility>

#include "core/errors.hpp"
#include "core/free_memory.hpp"
#include "core/parallel_for.hpp"
#include "identify/plan/bandwidth.hpp"
#include "identify/pipeline/pipeline_fold.hpp"
#include "identify/pipeline/state_source.hpp"
#include "identify/pipeline/torque_smoothing.hpp"
#include "jacobid/baseline/butterworth.hpp"
#include "jacobid/baseline/euler_difference.hpp"
#include "jacobid/frequency_response.hpp"
#include "jacobid/kernel_design.hpp"
#include "signal/baseline_response.hpp"
#include "signal/fft_convolver.hpp"
#include "signal/kernel_design_checked.hpp"

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

std::vector<double> design_or_throw(const KernelParams& p) {
    return signal::design_kernel_or_throw(p, [&](KernelStatus) { return fmt::format("Jacobi order-{} differentiator", p.order); });
}

// The largest window searched for a cutoff: the log's length, within 2 000 001 taps.
std::size_t max_taps_for(std::size_t samples) { return std::max<std::size_t>(std::min<std::size_t>(samples, 2'000'001), 3); }

// A Jacobi velocity kernel (the pipeline's kappa, mu, q) whose cutoff is closest to `cutoff`.
std::vector<double> coulomb_velocity_kernel(const PipelineSettings& s, double ts, std::size_t n, double cutoff) {
    return signal::kernel_for_cutoff_or_throw(jacobi_params(s, 1, ts), cutoff, max_taps_for(n), "Coulomb velocity window design");
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
    signal::filtfilt_or_throw(f, x.data(), y.data(), x.size(), w);
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
        std::vector<double> scratch(max_taps_for(n));
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
            signal::filtfilt_or_throw(fq, log.q[j]->data(), e.q[j].data(), n, workspace);
            signal::filtfilt_or_throw(fq, log.tau[j]->data(), e.tau[j].data(), n, workspace);
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
                signal::filtfilt_or_throw(fc, log.q[j]->data(), qf.data(), n, workspace);
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
                signal::filtfilt_or_throw(fq, measured->data(), e.qd[j].data(), n, workspace);
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

}  // namespace jacobid::identify
