// SPDX-License-Identifier: MIT
#include "signal/differentiation.hpp"

#include <fmt/core.h>

#include <cmath>

#include "core/errors.hpp"
#include "jacobid/baseline/euler_difference.hpp"
#include "jacobid/baseline/filtfilt.hpp"
#include "jacobid/batch_differentiate.hpp"
#include "jacobid/kernel_design.hpp"
#include "signal/fft_convolver.hpp"

namespace jacobid::signal {

Estimate jacobi_estimate(const KernelParams& params, const std::vector<double>& x, const std::string& what) {
    std::vector<double> weights(tap_count(params));
    const KernelStatus ks = design_kernel(params, Span<double>(weights));
    if (ks != KernelStatus::Ok) throw InputError(fmt::format("{}: {}", what, describe(ks)));
    return jacobi_estimate(params, weights, x, what);
}

Estimate jacobi_estimate(const KernelParams& params, const std::vector<double>& weights, const std::vector<double>& x,
                         const std::string& what) {
    return jacobi_estimate(params, weights, Span<const double>(x), what);
}

Estimate jacobi_estimate(const KernelParams& params, const std::vector<double>& weights, Span<const double> x, const std::string& what) {
    if (x.size() < weights.size()) {
        throw InputError(fmt::format("{}: {} samples, shorter than the differentiator window of {} taps ({} s)", what, x.size(),
                                          weights.size(), static_cast<double>(weights.size() - 1) * params.sample_period));
    }
    Estimate e;
    e.values.resize(batch_output_size(x.size(), weights.size()));
    const BatchStatus bs = differentiate_batch(Span<const double>(weights), x, Span<double>(e.values));
    if (bs != BatchStatus::Ok) throw InputError(fmt::format("{}: {}", what, describe(bs)));
    e.first_index = batch_offset_samples(weights.size(), params.xi);
    return e;
}

std::size_t butterworth_edge_samples(double cutoff_hz, double ts) {
    return static_cast<std::size_t>(std::ceil(3.0 / (cutoff_hz * ts)));
}

Estimate butterworth_euler_estimate(const ButterworthSos& sos, int order, double ts, const std::vector<double>& x, std::size_t crop,
                                    const std::string& what) {
    std::vector<double> filtered(x.size());
    std::vector<double> workspace(sosfiltfilt_workspace_size(sos));
    const FilterStatus fs = sosfiltfilt(sos, Span<const double>(x), Span<double>(filtered), Span<double>(workspace));
    if (fs != FilterStatus::Ok) {
        throw InputError(fmt::format("{}: {} samples: Butterworth forward-backward filter: {}", what, x.size(), describe(fs)));
    }
    std::vector<double> derivative(x.size());
    ValidRange valid{0, x.size()};
    if (order == 0) {
        derivative = filtered;
    } else {
        const DifferenceResult r = order == 1 ? euler_first_derivative(Span<const double>(filtered), ts, Span<double>(derivative))
                                              : euler_second_derivative(Span<const double>(filtered), ts, Span<double>(derivative));
        if (r.status != FilterStatus::Ok) throw InputError(fmt::format("{}: Euler difference: {}", what, describe(r.status)));
        valid = r.valid;
    }
    const std::size_t begin = std::max(valid.begin, crop);
    const std::size_t end = valid.end > crop ? std::min(valid.end, x.size() - crop) : 0;
    if (end <= begin) {
        throw InputError(fmt::format("{}: {} samples leave nothing after removing {} edge samples at each end", what, x.size(), crop));
    }
    Estimate e;
    e.values.assign(derivative.begin() + static_cast<std::ptrdiff_t>(begin), derivative.begin() + static_cast<std::ptrdiff_t>(end));
    e.first_index = static_cast<double>(begin);
    return e;
}

}  // namespace jacobid::signal
