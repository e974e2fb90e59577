// SPDX-License-Identifier: MIT
#pragma once
// Bandwidth of the motion in a log, used to choose the differentiator windows and the decimation filter
// when the user gives none (docs/method.md, "Motion bandwidth estimate"). Per joint, from a Welch spectrum
// (Hann, 50 % overlap) of the first difference of the position:
//  - isolated jumps (a run of at most 3 differences more than 10 x the 99th percentile of |difference|,
//    e.g. runs joined end to end, a glitch) are breaks, not motion: they are bridged before the spectrum;
//  - the noise floor (white position noise, from the median of the spectrum's 0.25..0.4 fs band; it rises
//    as f^2 in the velocity) is removed;
//  - `energy_frequency`: the frequency below which `fraction` (99 %) of the remaining velocity energy lies
//    (summed over the joints used: what a position-loop bandwidth shapes);
//  - `noise_limit`: the highest bandwidth B at which the floor's share of the acceleration energy below the
//    differentiator cutoff (cutoff_ratio x B) stays under kAccelerationNoiseShare. Coarse encoders and
//    noisy sensors need a lower bandwidth than their motion's, measured against simulated truth and the
//    pendubot (docs/method.md).
// The velocity's estimate is the smaller of the two.
//
// The torque's bandwidth (estimate_torque_bandwidth): identify smooths the torque with the velocity
// kernel's low-pass and computes the regressor from the filtered positions; the regressor is nonlinear in
// q and qd, so the two sides only agree where that low-pass is flat over the torque's band, which on a
// motion that swings the joints over most of their range reaches several times the velocity's
// (docs/excite.md, "Identifying the design"). Per joint, from a Welch spectrum of the torque itself (not
// differenced; the same segments and window), its white noise floor (median of the spectrum over
// 0.25..0.4 fs, scaled from median to mean: above the torque of any motion a position loop follows) is
// removed; its bandwidth is the frequency below which `fraction` (99 %) of the rest lies, counting bins up
// to 0.25 fs and the widest differentiator cutoff the position noise allows. The torques' bandwidth is the
// widest over the joints whose torque variance is at least 100 x their floor's (RMS 10 x): each joint's
// equations are biased when the smoothing cuts its own torque.
// estimate_bandwidth: the motion's bandwidth (F_p at 5 x) stays the velocity's; the differentiators and the
// torque's smoothing follow `differentiator_frequency` = min(max(velocity's energy frequency, torque's), noise
// limit): F_p is one linear filter on both sides and biases nothing, the differentiators' low-pass does.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace jacobid::identify {

// Share of the floor-removed velocity energy below the bandwidth (`fraction`).
inline constexpr double kMotionEnergyFraction = 0.99;

// Largest share of the acceleration energy (below the differentiator cutoff) the position noise may hold.
inline constexpr double kAccelerationNoiseShare = 2e-4;

struct JointBandwidth {
    std::string name;
    double frequency = 0.0;          // Hz, this joint alone: min(energy_frequency, noise_limit)
    double energy_frequency = 0.0;   // Hz, `fraction` of its floor-removed velocity energy
    double noise_limit = 0.0;        // Hz, infinity when the floor never limits it
    double noise_rms = 0.0;          // rad, RMS of the white position noise the floor stands for
    double floor_fraction = 0.0;     // share of its velocity-difference energy removed as noise floor
    double quantization_step = 0.0;  // rad, step of the grid its positions lie on (0: none found)
    std::size_t jumps = 0;           // isolated jumps / outliers bridged
    bool moving = false;             // its position is not constant
    bool used = false;               // counted in the combined estimate (moves and rises above its floor)
};

struct JointTorqueBandwidth {
    std::string name;
    double frequency = 0.0;       // Hz, `fraction` of its own floor-removed torque energy (0: not moving)
    double noise_rms = 0.0;       // torque units (N.m, or the log's current), RMS of the white floor
    double floor_fraction = 0.0;  // share of its torque energy (mean removed) removed as noise floor
    bool moving = false;          // its torque is not constant
    bool used = false;            // counted in the combined estimate (variance >= 100 x its floor's)
};

struct TorqueBandwidth {
    double frequency = 0.0;   // Hz, the widest of the joints used; 0: no joint used (or not estimated)
    double resolution = 0.0;  // Hz, bin width of the spectrum
    double highest = 0.0;     // Hz, the bins counted stop here (0.25 fs, or the widest cutoff the position noise allows)
    bool noise_known = false; // the floors were given (estimate_torque_bandwidth's noise_std), not estimated
    std::vector<JointTorqueBandwidth> joints;
    bool estimated() const { return !joints.empty(); }
};

struct BandwidthEstimate {
    double frequency = 0.0;         // Hz, min(energy_frequency, noise_limit): the motion's bandwidth (F_p)
    double resolution = 0.0;        // Hz, bin width of the spectrum
    bool moving = false;            // false: no velocity energy at all (every joint constant)
    double energy_frequency = 0.0;  // Hz, over the joints used
    double noise_limit = 0.0;       // Hz, over the joints used; infinity when the floor never limits
    bool noise_limited = false;     // frequency == noise_limit < energy_frequency
    bool all_below_floor = false;   // no moving joint rose above its floor: all of them were used
    std::size_t jumps = 0;          // over all joints
    std::vector<JointBandwidth> joints;
    std::string description;        // one line: what was estimated and from what
    // From the torques (estimate_bandwidth; empty when not estimated: estimate_motion_bandwidth alone).
    TorqueBandwidth torque;
    // Hz, min(max(energy_frequency, torque.frequency), noise_limit): the differentiators' and the torque
    // smoothing's bandwidth (their cutoff at cutoff_ratio x it); `frequency` when the torques were not estimated.
    double differentiator_frequency = 0.0;
    bool torque_wider = false;  // torque.frequency > energy_frequency: the torque's band sets differentiator_frequency
    bool torque_noise_limited = false;  // torque_wider, and the noise limit holds differentiator_frequency below the torque's band
};

// `names` label the joints in the description (default "joint 1", ...); `cutoff_ratio` is the
// differentiator cutoff as a multiple of the bandwidth (PipelineSettings::differentiator_ratio); the joints
// are estimated on up to `threads` threads (the result does not depend on it).
BandwidthEstimate estimate_motion_bandwidth(const std::vector<const std::vector<double>*>& positions, double sample_period,
                                            const std::vector<std::string>& names = {}, double cutoff_ratio = 10.0,
                                            double fraction = kMotionEnergyFraction, int threads = 1);

// The torques' bandwidth (the rule above), joints labelled by `names` (default "joint 1", ...); bins
// counted up to min(0.25 fs, highest). `noise_std` (one per joint, white noise std per sample), when given,
// replaces the estimated floors (excite: the noise the design is made for, on a noise-free model torque).
// `shift`: samples by which the torques were read later by linear interpolation (LogColumns::tau_aligned_by /
// Ts); its fractional part's low-pass is divided out of the spectra.
TorqueBandwidth estimate_torque_bandwidth(const std::vector<const std::vector<double>*>& torques, double sample_period,
                                          const std::vector<std::string>& names = {}, double highest = std::numeric_limits<double>::infinity(),
                                          double fraction = kMotionEnergyFraction, int threads = 1, const std::vector<double>& noise_std = {},
                                          double shift = 0.0);

// `motion` (estimate_motion_bandwidth) with `torque`'s band: differentiator_frequency = min(max(energy frequency,
// torque frequency), noise limit), flags and description updated. The bins the torque's estimate may count
// for `motion`: torque_highest.
double torque_highest(const BandwidthEstimate& motion, double cutoff_ratio);
BandwidthEstimate with_torque(BandwidthEstimate motion, TorqueBandwidth torque, double cutoff_ratio);

// identify's automatic bandwidths: the positions' estimate, its differentiators widened to the torques' band.
BandwidthEstimate estimate_bandwidth(const std::vector<const std::vector<double>*>& positions, const std::vector<const std::vector<double>*>& torques,
                                     double sample_period, const std::vector<std::string>& position_names = {},
                                     const std::vector<std::string>& torque_names = {}, double cutoff_ratio = 10.0,
                                     double fraction = kMotionEnergyFraction, int threads = 1, double torque_shift = 0.0);

}  // namespace jacobid::identify
