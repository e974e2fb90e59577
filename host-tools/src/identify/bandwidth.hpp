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
// The estimate is the smaller of the two.
#include <cstddef>
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

struct BandwidthEstimate {
    double frequency = 0.0;         // Hz, min(energy_frequency, noise_limit)
    double resolution = 0.0;        // Hz, bin width of the spectrum
    bool moving = false;            // false: no velocity energy at all (every joint constant)
    double energy_frequency = 0.0;  // Hz, over the joints used
    double noise_limit = 0.0;       // Hz, over the joints used; infinity when the floor never limits
    bool noise_limited = false;     // frequency == noise_limit < energy_frequency
    std::size_t jumps = 0;          // over all joints
    std::vector<JointBandwidth> joints;
    std::string description;        // one line: what was estimated and from what
};

// `names` label the joints in the description (default "joint 1", ...); `cutoff_ratio` is the
// differentiator cutoff as a multiple of the bandwidth (PipelineSettings::differentiator_ratio); the joints
// are estimated on up to `threads` threads (the result does not depend on it).
BandwidthEstimate estimate_motion_bandwidth(const std::vector<const std::vector<double>*>& positions, double sample_period,
                                            const std::vector<std::string>& names = {}, double cutoff_ratio = 10.0,
                                            double fraction = kMotionEnergyFraction, int threads = 1);

}  // namespace jacobid::identify
