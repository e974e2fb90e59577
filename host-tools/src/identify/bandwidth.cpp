// SPDX-License-Identifier: MIT
#include "identify/bandwidth.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace jacobid::identify {

BandwidthEstimate estimate_motion_bandwidth(const std::vector<const std::vector<double>*>& positions, double sample_period,
                                            double fraction) {
    BandwidthEstimate result;
    if (positions.empty() || positions.front()->size() < 16) return result;
    const std::size_t n = positions.front()->size() - 1;  // differences
    // Segments of ~20 s (resolution 0.05 Hz), a power of two, at most the record.
    std::size_t seg = 256;
    while (seg * 2 <= n && static_cast<double>(seg) * sample_period < 20.0) seg *= 2;
    seg = std::min(seg, n);
    const std::size_t hop = seg / 2;
    const std::size_t segments = n >= seg ? (n - seg) / hop + 1 : 1;
    // At most 64 segments spread over the record: enough averaging, bounded cost on hour-long logs.
    const std::size_t used = std::min<std::size_t>(segments, 64);
    std::vector<double> in(seg), window(seg), power(seg / 2 + 1, 0.0);
    auto* out = static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * (seg / 2 + 1)));
    std::unique_ptr<fftw_complex, decltype(&fftw_free)> out_guard(out, &fftw_free);
    fftw_plan plan = fftw_plan_dft_r2c_1d(static_cast<int>(seg), in.data(), out, FFTW_ESTIMATE);
    for (std::size_t k = 0; k < seg; ++k) window[k] = 0.5 - 0.5 * std::cos(2.0 * M_PI * static_cast<double>(k) / static_cast<double>(seg));
    for (const auto* q : positions) {
        for (std::size_t s = 0; s < used; ++s) {
            const std::size_t start = used > 1 ? (segments - 1) * s / (used - 1) * hop : 0;
            double mean = 0.0;
            for (std::size_t k = 0; k < seg; ++k) mean += (*q)[start + k + 1] - (*q)[start + k];
            mean /= static_cast<double>(seg);
            for (std::size_t k = 0; k < seg; ++k) in[k] = ((*q)[start + k + 1] - (*q)[start + k] - mean) * window[k];
            fftw_execute(plan);
            for (std::size_t f = 0; f < power.size(); ++f) power[f] += out[f][0] * out[f][0] + out[f][1] * out[f][1];
        }
    }
    fftw_destroy_plan(plan);
    double total = 0.0;
    for (double p : power) total += p;
    result.resolution = 1.0 / (static_cast<double>(seg) * sample_period);
    if (!(total > 0.0)) return result;
    result.moving = true;
    double cumulative = 0.0;
    for (std::size_t f = 0; f < power.size(); ++f) {
        cumulative += power[f];
        if (cumulative >= fraction * total) {
            result.frequency = std::max(static_cast<double>(f), 1.0) * result.resolution;
            break;
        }
    }
    return result;
}

}  // namespace jacobid::identify
