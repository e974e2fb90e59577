// SPDX-License-Identifier: MIT
#pragma once
// Filter and kernel design for whole signals, with the host's error convention: the core's designers
// (lib/: design_kernel, window_for_cutoff, sosfiltfilt) return a status; these turn a failed one into an
// InputError that names what was being designed. The identification pipeline, the commands' kernel options
// and the Python module all design through them.
#include <functional>
#include <string>
#include <vector>

#include "jacobid/kernel_params.hpp"
#include "signal/baseline_response.hpp"

namespace jacobid::signal {

// The weights of the Jacobi kernel `p` (oldest sample first). InputError "<what(status)>: <the status
// described>" when the parameters are refused; `what` names the option or stage that gave them.
std::vector<double> design_kernel_or_throw(const KernelParams& p, const std::function<std::string(KernelStatus)>& what);

// The Jacobi kernel of `p`'s order, kappa, mu, q and discretization whose odd-tap window gives the cutoff
// closest to `cutoff_hz`, searched up to `max_taps` taps. InputError "<what>: <status>" otherwise.
std::vector<double> kernel_for_cutoff_or_throw(KernelParams p, double cutoff_hz, std::size_t max_taps, const std::string& what);

// Forward-backward (zero-phase) filtering of x[0, n) into y by `sos`, growing `workspace` as needed.
// InputError naming the sample count when the signal is too short for the filter's padding.
void filtfilt_or_throw(const ButterworthSos& sos, const double* x, double* y, std::size_t n, std::vector<double>& workspace);

}  // namespace jacobid::signal
