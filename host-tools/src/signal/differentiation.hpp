// SPDX-License-Identifier: MIT
#pragma once
// Whole-signal differentiation on the host: the Jacobi kernel (central or not) and the classic
// Butterworth forward-backward + central Euler pipeline. Each result says which input sample its first
// value refers to; values near the ends that a method cannot compute are dropped, never invented.
#include <cstddef>
#include <string>
#include <vector>

#include "jacobid/kernel_params.hpp"
#include "jacobid/span.hpp"
#include "signal/baseline_response.hpp"

namespace jacobid::signal {

struct Estimate {
    std::vector<double> values;
    double first_index = 0.0;  // input index (fractional for a non-integer delay) of values[0]
};

// Jacobi estimate of x^(n) with the kernel of `params`; throws InputError naming `what` when x is shorter
// than the window. Long kernels go through the FFT path (differentiate_batch).
Estimate jacobi_estimate(const KernelParams& params, const std::vector<double>& x, const std::string& what);
// The same with weights already designed from `params` (oldest sample first).
Estimate jacobi_estimate(const KernelParams& params, const std::vector<double>& weights, const std::vector<double>& x,
                         const std::string& what);
// The same on samples held elsewhere (e.g. a numpy array in the Python module): read in place, not copied.
Estimate jacobi_estimate(const KernelParams& params, const std::vector<double>& weights, Span<const double> x, const std::string& what);

// Forward-backward Butterworth, then the central Euler difference of `order` (0, 1 or 2). The first and
// last `crop` samples (the filter's end transients) and the ends without a central difference are dropped.
Estimate butterworth_euler_estimate(const ButterworthSos& sos, int order, double ts, const std::vector<double>& x,
                                    std::size_t crop, const std::string& what);

// The end transient of a forward-backward low-pass with cutoff fc lasts a few 1/fc (docs/method.md, "Pitfalls"):
// 3 / fc, in samples.
std::size_t butterworth_edge_samples(double cutoff_hz, double ts);

}  // namespace jacobid::signal
