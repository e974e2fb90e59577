// SPDX-License-Identifier: MIT
#pragma once
// Decimation by an integer factor q: zero-phase low-pass (sosfiltfilt), then every q-th sample starting at
// index 0. With the default low-pass this is scipy.signal.decimate(x, q) (ftype='iir', zero_phase=True);
// any other SosCascade (e.g. the paper's Butterworth) can be the low-pass instead. The low-pass must cut
// below the new Nyquist frequency and, in the identification pipeline, below the differentiators' cutoff
// (docs/method.md, "Pitfalls").
#include <cstddef>

#include "jacobid/baseline/butterworth.hpp"
#include "jacobid/baseline/filter_status.hpp"
#include "jacobid/baseline/filtfilt.hpp"
#include "jacobid/baseline/sos.hpp"
#include "jacobid/span.hpp"

namespace jacobid {

// scipy.signal.decimate's default IIR low-pass: Chebyshev I, order 8, 0.05 dB ripple, edge 0.8 / q.
constexpr int kDecimationLowpassOrder = 8;
constexpr double kDecimationLowpassRippleDb = 0.05;
constexpr double kDecimationLowpassEdge = 0.8;  // of the decimated Nyquist frequency
using DecimationLowpass = SosCascade<static_cast<std::size_t>(kDecimationLowpassOrder) / 2>;

// Samples kept from input_size samples: indices 0, q, 2q, ... (0 for an invalid factor).
constexpr std::size_t decimated_size(std::size_t input_size, std::size_t factor) noexcept {
    return factor == 0 ? 0 : (input_size + factor - 1) / factor;
}

// Workspace decimate needs: the full-rate filtered signal plus sosfiltfilt's workspace.
template <std::size_t MaxSections>
std::size_t decimate_workspace_size(std::size_t input_size, const SosCascade<MaxSections>& lowpass) noexcept {
    return input_size + sosfiltfilt_workspace_size(lowpass);
}

// Workspace of the default decimate. The order-8 Chebyshev low-pass has no first-order section, so its
// padlen is the largest one of a 4-section cascade and the bound is exact.
constexpr std::size_t default_decimate_workspace_size(std::size_t input_size) noexcept {
    return input_size + sosfiltfilt_max_workspace_size<DecimationLowpass::capacity>();
}

// The default low-pass for factor q: scipy.signal.cheby1(8, 0.05, 0.8 / q, output='sos').
// Design it once with this and call the cascade overload of decimate() when decimating repeatedly.
// Errors: InvalidFactor (q < 1).
inline FilterStatus decimation_lowpass(std::size_t factor, DecimationLowpass& lowpass) noexcept {
    if (factor < 1) return FilterStatus::InvalidFactor;
    // cheby1 on the normalized axis: sample rate 2, so the cutoff is scipy's Wn itself.
    return chebyshev1_lowpass(kDecimationLowpassOrder, kDecimationLowpassRippleDb,
                              kDecimationLowpassEdge / static_cast<double>(factor), 2.0, lowpass);
}

// y = sosfiltfilt(lowpass, x)[::factor]. y.size() must be decimated_size(x.size(), factor); y may
// overlap x. workspace: at least decimate_workspace_size(x.size(), lowpass) doubles.
// Errors, checked in this order: InvalidFactor, InvalidCascade, OutputSizeMismatch, SignalTooShort
// (x.size() <= sosfiltfilt_padlen(lowpass)), WorkspaceTooSmall. y is not written on error.
template <std::size_t MaxSections>
FilterStatus decimate(const SosCascade<MaxSections>& lowpass, std::size_t factor, Span<const double> x, Span<double> y,
                      Span<double> workspace) noexcept {
    if (factor < 1) return FilterStatus::InvalidFactor;
    const FilterStatus cascade_status = validate_cascade(lowpass);
    if (cascade_status != FilterStatus::Ok) return cascade_status;
    if (y.size() != decimated_size(x.size(), factor)) return FilterStatus::OutputSizeMismatch;
    if (x.size() <= sosfiltfilt_padlen(lowpass)) return FilterStatus::SignalTooShort;
    if (workspace.size() < decimate_workspace_size(x.size(), lowpass)) return FilterStatus::WorkspaceTooSmall;

    const std::size_t n = x.size();
    const Span<double> filtered = workspace.subspan(0, n);
    const FilterStatus status = sosfiltfilt(lowpass, x, filtered, workspace.subspan(n, workspace.size() - n));
    if (status != FilterStatus::Ok) return status;
    for (std::size_t i = 0; i < y.size(); ++i) y[i] = filtered[i * factor];
    return FilterStatus::Ok;
}

// scipy.signal.decimate(x, factor) with its default Chebyshev I low-pass (designed on each call).
// Sizes and errors as the cascade overload; workspace: default_decimate_workspace_size(x.size()).
inline FilterStatus decimate(std::size_t factor, Span<const double> x, Span<double> y,
                             Span<double> workspace) noexcept {
    DecimationLowpass lowpass;
    const FilterStatus design_status = decimation_lowpass(factor, lowpass);
    if (design_status != FilterStatus::Ok) return design_status;
    return decimate(lowpass, factor, x, y, workspace);
}

}  // namespace jacobid
