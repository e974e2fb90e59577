// SPDX-License-Identifier: MIT
#include "excite/identification_bandwidth.hpp"

#include <fftw3.h>

#include <algorithm>
#include <mutex>
#include <numeric>
#include <stdexcept>

#include "signal/fftw_planner.hpp"

namespace jacobid::excite {

double energy_frequency(const std::vector<std::vector<double>>& signals, const std::vector<double>& weights, double rate, double fraction) {
    if (signals.empty() || signals.front().size() < 2 || weights.size() != signals.size()) {
        throw std::invalid_argument("energy_frequency: signals of at least 2 samples, one weight each");
    }
    const std::size_t n = signals.front().size(), bins = n / 2 + 1;
    std::vector<double> buffer(n), energy(bins, 0.0);
    auto* spectrum = static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * bins));
    fftw_plan plan = nullptr;
    {
        const std::lock_guard<std::mutex> lock(signal::fftw_planner_mutex());
        plan = fftw_plan_dft_r2c_1d(static_cast<int>(n), buffer.data(), spectrum, FFTW_ESTIMATE);
    }
    for (std::size_t s = 0; s < signals.size(); ++s) {
        const double mean = std::accumulate(signals[s].begin(), signals[s].end(), 0.0) / static_cast<double>(n);
        for (std::size_t i = 0; i < n; ++i) buffer[i] = weights[s] * (signals[s][i] - mean);
        fftw_execute(plan);
        for (std::size_t k = 0; k < bins; ++k) energy[k] += spectrum[k][0] * spectrum[k][0] + spectrum[k][1] * spectrum[k][1];
    }
    {
        const std::lock_guard<std::mutex> lock(signal::fftw_planner_mutex());
        fftw_destroy_plan(plan);
    }
    fftw_free(spectrum);
    const double total = std::accumulate(energy.begin(), energy.end(), 0.0);
    if (!(total > 0.0)) return 0.0;
    double sum = 0.0;
    for (std::size_t k = 0; k < bins; ++k) {
        sum += energy[k];
        if (sum >= fraction * total) return static_cast<double>(k) * rate / static_cast<double>(n);
    }
    return rate / 2.0;
}

IdentificationBandwidth identification_bandwidth(const std::vector<std::vector<double>>& qd, const std::vector<std::vector<double>>& tau,
                                                 const Eigen::VectorXd& noise_std, double rate) {
    IdentificationBandwidth b;
    b.velocity_hz = energy_frequency(qd, std::vector<double>(qd.size(), 1.0), rate);
    std::vector<double> weights;
    for (Eigen::Index j = 0; j < noise_std.size(); ++j) weights.push_back(1.0 / noise_std[j]);
    b.torque_hz = energy_frequency(tau, weights, rate);
    return b;
}

}  // namespace jacobid::excite
