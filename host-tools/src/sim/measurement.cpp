// SPDX-License-Identifier: MIT
#include "sim/measurement.hpp"

#include <cmath>

namespace jacobid::sim {

MeasurementModel::MeasurementModel(MeasurementSettings settings) : settings_(std::move(settings)), rng_(settings_.seed), position_rng_(settings_.seed + 1) {}

double MeasurementModel::position(double q) {
    if (settings_.position_noise > 0.0) q += settings_.position_noise * normal_(position_rng_);
    if (!(settings_.encoder_counts_per_rev > 0.0)) return q;
    const double count = 2.0 * M_PI / settings_.encoder_counts_per_rev;
    return std::round(q / count) * count;
}

double MeasurementModel::torque(std::size_t joint, double tau, double q) {
    double measured = tau;
    if (joint < settings_.ripple_amplitude.size() && settings_.ripple_amplitude[joint] != 0.0) {
        measured += settings_.ripple_amplitude[joint] * std::sin(settings_.ripple_periods_per_rev * q);
    }
    if (joint < settings_.torque_noise.size() && settings_.torque_noise[joint] > 0.0) {
        measured += settings_.torque_noise[joint] * normal_(rng_);
    }
    return measured;
}

}  // namespace jacobid::sim
