// SPDX-License-Identifier: MIT
#pragma once
// What the log records instead of the truth: encoder quantization of the positions (optionally with white position noise), Gaussian noise on the
// torques (per joint) and an optional position-dependent torque ripple (cogging-like: amplitude *
// sin(periods * q)), which is a real drive effect the rigid-body model does not contain, and an optional
// delay of the torque channel against the position channel (applied by the simulator, torque_delay_line.hpp).
#include <cstdint>
#include <random>
#include <vector>

namespace jacobid::sim {

struct MeasurementSettings {
    double encoder_counts_per_rev = 65536.0;  // 0: no quantization
    std::vector<double> torque_noise;         // N.m standard deviation per joint; empty: none
    std::vector<double> ripple_amplitude;     // N.m per joint; empty: none
    double ripple_periods_per_rev = 50.0;
    double torque_delay = 0.0;  // s: the logged torque lags the positions (torque_delay effect); 0: none
    // rad standard deviation of white noise added to every measured position (before quantization), e.g.
    // an encoder's interpolation error; 0: none. Drawn from its own stream (seed + 1), so that adding it
    // leaves the torque noise of a seed unchanged.
    double position_noise = 0.0;
    std::uint64_t seed = 2;
};

class MeasurementModel {
public:
    explicit MeasurementModel(MeasurementSettings settings);
    const MeasurementSettings& settings() const { return settings_; }
    // Quantized position: the encoder reports whole counts (rounding to the nearest count).
    double position(double q);
    // Measured torque of `joint` given the true motor torque and the true position.
    double torque(std::size_t joint, double tau, double q);

private:
    MeasurementSettings settings_;
    std::mt19937_64 rng_;
    std::mt19937_64 position_rng_;
    std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace jacobid::sim
