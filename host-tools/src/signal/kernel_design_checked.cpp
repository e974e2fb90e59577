// SPDX-License-Identifier: MIT
#include "signal/kernel_design_checked.hpp"

#include <fmt/core.h>

#include "core/errors.hpp"
#include "jacobid/baseline/filtfilt.hpp"
#include "jacobid/frequency_response.hpp"
#include "jacobid/kernel_design.hpp"

namespace jacobid::signal {

std::vector<double> design_kernel_or_throw(const KernelParams& p, const std::function<std::string(KernelStatus)>& what) {
    std::vector<double> weights(tap_count(p));
    const KernelStatus status = design_kernel(p, Span<double>(weights));
    if (status != KernelStatus::Ok) throw InputError(fmt::format("{}: {}", what(status), describe(status)));
    return weights;
}

std::vector<double> kernel_for_cutoff_or_throw(KernelParams p, double cutoff_hz, std::size_t max_taps, const std::string& what) {
    std::vector<double> scratch(max_taps);
    const WindowDesign d = window_for_cutoff(p, cutoff_hz, true, Span<double>(scratch));
    if (d.status != KernelStatus::Ok) throw InputError(fmt::format("{}: {}", what, describe(d.status)));
    p.window = d.window;
    return design_kernel_or_throw(p, [&](KernelStatus) { return what; });
}

void filtfilt_or_throw(const ButterworthSos& sos, const double* x, double* y, std::size_t n, std::vector<double>& workspace) {
    workspace.resize(sosfiltfilt_workspace_size(sos));
    const FilterStatus status = sosfiltfilt(sos, Span<const double>(x, n), Span<double>(y, n), Span<double>(workspace));
    if (status != FilterStatus::Ok) throw InputError(fmt::format("zero-phase filter on {} samples: {}", n, describe(status)));
}

}  // namespace jacobid::signal
