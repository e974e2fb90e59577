// SPDX-License-Identifier: MIT
#pragma once
// Zero-phase forward-backward filtering with scipy.signal.sosfiltfilt's edge handling (padtype='odd',
// default padlen): the signal is extended at both ends by its point reflection, filtered forward from the
// steady state of its first extended sample, filtered backward from the steady state of the last forward
// output, and the extensions are dropped. Same edges as scipy means the end transients docs/method.md ("Pitfalls")
// tell us to crop are the same ones in both implementations.
#include <cstddef>

#include "jacobid/baseline/filter_status.hpp"
#include "jacobid/baseline/sos.hpp"
#include "jacobid/span.hpp"

namespace jacobid {

// scipy's default padlen: 3 * ntaps, ntaps = 2 n_sections + 1 - min(#(b2 == 0), #(a2 == 0)), i.e. the
// order of the cascade's transfer function plus one once first-order sections are counted as such.
template <std::size_t MaxSections>
std::size_t sosfiltfilt_padlen(const SosCascade<MaxSections>& cascade) noexcept {
    const std::size_t count = cascade.count < MaxSections ? cascade.count : MaxSections;
    std::size_t zero_b2 = 0;
    std::size_t zero_a2 = 0;
    for (std::size_t i = 0; i < count; ++i) {
        if (cascade.sections[i][2] == 0.0) ++zero_b2;
        if (cascade.sections[i][5] == 0.0) ++zero_a2;
    }
    const std::size_t taps = 2 * count + 1 - (zero_b2 < zero_a2 ? zero_b2 : zero_a2);
    return 3 * taps;
}

// Workspace sosfiltfilt needs for this cascade: the two edge extensions (the middle is filtered in y).
template <std::size_t MaxSections>
std::size_t sosfiltfilt_workspace_size(const SosCascade<MaxSections>& cascade) noexcept {
    return 2 * sosfiltfilt_padlen(cascade);
}

// Upper bound of sosfiltfilt_workspace_size over every cascade of this capacity, for static buffers.
template <std::size_t MaxSections>
constexpr std::size_t sosfiltfilt_max_workspace_size() noexcept {
    return 2 * 3 * (2 * MaxSections + 1);
}

namespace filtfilt_detail {

template <std::size_t MaxSections>
void filter_forward_in_place(SosFilterState<MaxSections>& filter, Span<double> data) noexcept {
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = filter.step(data[i]);
}

template <std::size_t MaxSections>
void filter_backward_in_place(SosFilterState<MaxSections>& filter, Span<double> data) noexcept {
    for (std::size_t i = data.size(); i-- > 0;) data[i] = filter.step(data[i]);
}

}  // namespace filtfilt_detail

// y = scipy.signal.sosfiltfilt(cascade, x). y.size() must equal x.size(); y may be x itself (in place).
// workspace: at least sosfiltfilt_workspace_size(cascade) doubles (never more than
// sosfiltfilt_max_workspace_size<MaxSections>()); its content on entry does not matter.
// Errors, checked in this order: InvalidCascade, OutputSizeMismatch, SignalTooShort (x.size() <= padlen,
// where scipy raises), WorkspaceTooSmall. y is not written on error.
template <std::size_t MaxSections>
FilterStatus sosfiltfilt(const SosCascade<MaxSections>& cascade, Span<const double> x, Span<double> y,
                         Span<double> workspace) noexcept {
    const FilterStatus cascade_status = validate_cascade(cascade);
    if (cascade_status != FilterStatus::Ok) return cascade_status;
    if (y.size() != x.size()) return FilterStatus::OutputSizeMismatch;
    const std::size_t padlen = sosfiltfilt_padlen(cascade);
    const std::size_t n = x.size();
    if (n <= padlen) return FilterStatus::SignalTooShort;
    if (workspace.size() < 2 * padlen) return FilterStatus::WorkspaceTooSmall;

    // The extended signal is [left | x | right]; left and right live in the workspace, the middle in y.
    // Both extensions are built before y is written, so that y may alias x.
    const Span<double> left = workspace.subspan(0, padlen);
    const Span<double> right = workspace.subspan(padlen, padlen);
    const double first = x[0];
    const double last = x[n - 1];
    for (std::size_t i = 0; i < padlen; ++i) {
        left[i] = 2.0 * first - x[padlen - i];
        right[i] = 2.0 * last - x[n - 2 - i];
    }

    const SosState<MaxSections> steady_state = sosfilt_zi(cascade);
    SosFilterState<MaxSections> filter(cascade);

    filter.reset(steady_state, left[0]);
    filtfilt_detail::filter_forward_in_place(filter, left);
    for (std::size_t i = 0; i < n; ++i) y[i] = filter.step(x[i]);
    filtfilt_detail::filter_forward_in_place(filter, right);

    filter.reset(steady_state, right[padlen - 1]);
    filtfilt_detail::filter_backward_in_place(filter, right);
    filtfilt_detail::filter_backward_in_place(filter, y);
    // The backward pass over the left extension would only produce samples that are dropped.
    return FilterStatus::Ok;
}

}  // namespace jacobid
