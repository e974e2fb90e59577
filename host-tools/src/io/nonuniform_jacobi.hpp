// SPDX-License-Identifier: MIT
#pragma once
// The Jacobi estimator with weights for the actual sample times, the alternative to resampling a
// non-uniform log (docs/method.md, "Non-uniform sampling", where both are measured): at each requested
// instant c, the weighted least-squares polynomial of degree q + n in tau = (t - c) / h fitted to the
// samples inside [c - h, c + h], weight (1 - tau)^mu (1 + tau)^kappa times each sample's cell width, and
// its n-th derivative at xi. On a uniform grid this is design_exact (kernel_design.hpp); on any grid it is
// exact for polynomials of degree <= q + n.
#include <vector>

#include "jacobid/kernel_params.hpp"

namespace jacobid::io {

// Estimates at each time of `at` (NaN where the window does not lie inside [t.front(), t.back()] or holds
// fewer than q + n + 1 weighted samples). `p.sample_period` and `p.discretization` are not used.
std::vector<double> jacobi_at_sample_times(const KernelParams& p, const std::vector<double>& t, const std::vector<double>& x,
                                           const std::vector<double>& at);

}  // namespace jacobid::io
