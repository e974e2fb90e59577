// SPDX-License-Identifier: MIT
#pragma once
// A cascade of second-order sections (SOS) and its streaming direct-form-II-transposed state, with the
// same coefficient layout, recursion and steady-state initial conditions as scipy.signal (sosfilt,
// sosfilt_zi). Low-pass filters with low normalized cutoffs are only usable in this form (docs/method.md,
// "Pitfalls"), and keeping scipy's conventions lets the baseline be checked against it number for number.
#include <array>
#include <cstddef>

#include "jacobid/baseline/filter_status.hpp"

namespace jacobid {

// One section is [b0 b1 b2 a0 a1 a2] with a0 = 1 (scipy's layout):
//   H(z) = (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2).
using SosSection = std::array<double, 6>;

template <std::size_t MaxSections>
struct SosCascade {
    static_assert(MaxSections > 0, "a cascade holds at least one section");
    static constexpr std::size_t capacity = MaxSections;

    std::array<SosSection, MaxSections> sections{};
    std::size_t count = 0;  // sections in use, the first `count` entries; 0 is the identity filter

    // Gain at DC, H(z = 1): the product of the section gains.
    double dc_gain() const noexcept;
};

// H(z = 1) of one section, summed in scipy's order (b.sum() / a.sum()).
inline double section_dc_gain(const SosSection& s) noexcept { return (s[0] + s[1] + s[2]) / (s[3] + s[4] + s[5]); }

template <std::size_t MaxSections>
double SosCascade<MaxSections>::dc_gain() const noexcept {
    double gain = 1.0;
    for (std::size_t i = 0; i < count && i < MaxSections; ++i) gain *= section_dc_gain(sections[i]);
    return gain;
}

// A cascade filled by hand or received from elsewhere may be malformed; scipy rejects the same cases
// (a0 != 1), and a count above capacity would read past the array.
template <std::size_t MaxSections>
FilterStatus validate_cascade(const SosCascade<MaxSections>& cascade) noexcept {
    if (cascade.count > MaxSections) return FilterStatus::InvalidCascade;
    for (std::size_t i = 0; i < cascade.count; ++i) {
        if (cascade.sections[i][3] != 1.0) return FilterStatus::InvalidCascade;
    }
    return FilterStatus::Ok;
}

// The two delay registers of every section (scipy's zi, shape (n_sections, 2)).
template <std::size_t MaxSections>
using SosState = std::array<std::array<double, 2>, MaxSections>;

// Initial state for which the response to a unit step starts (and stays) at its steady state, as
// scipy.signal.sosfilt_zi: scale it by the first input sample to start a filter without a transient.
// Each section's zi solves zi = A zi + B (scipy's lfilter_zi); the 2x2 system is solved in closed form
// (the formula scipy's source notes next to its linear solve). Each section sees the steady-state output
// of the sections before it, hence the running DC-gain scale. Assumes no section has a pole at z = 1.
template <std::size_t MaxSections>
SosState<MaxSections> sosfilt_zi(const SosCascade<MaxSections>& cascade) noexcept {
    SosState<MaxSections> zi{};
    double scale = 1.0;
    for (std::size_t i = 0; i < cascade.count && i < MaxSections; ++i) {
        const SosSection& s = cascade.sections[i];
        const double b0 = s[0], b1 = s[1], b2 = s[2], a1 = s[4], a2 = s[5];
        const double rhs0 = b1 - a1 * b0;
        const double rhs1 = b2 - a2 * b0;
        const double z0 = (rhs0 + rhs1) / (1.0 + a1 + a2);
        zi[i][0] = scale * z0;
        zi[i][1] = scale * (rhs1 - a2 * z0);
        scale *= section_dc_gain(s);
    }
    return zi;
}

// Streaming filter: one sample in, one sample out, the recursion of scipy's sosfilt. It keeps its own copy
// of the coefficients so that it cannot dangle. Precondition: validate_cascade(cascade) == Ok (a larger
// count is clamped to the capacity rather than read out of bounds).
template <std::size_t MaxSections>
class SosFilterState {
public:
    explicit SosFilterState(const SosCascade<MaxSections>& cascade) noexcept
        : cascade_(cascade), sections_in_use_(cascade.count < MaxSections ? cascade.count : MaxSections) {}

    // Zero state: the filter behaves as if all past inputs were 0.
    void reset() noexcept { state_ = SosState<MaxSections>{}; }

    // State initial * scale (scipy: sosfilt(sos, x, zi=initial * scale)); with sosfilt_zi(cascade) and
    // scale = first input sample the output starts in steady state.
    void reset(const SosState<MaxSections>& initial, double scale) noexcept {
        for (std::size_t i = 0; i < MaxSections; ++i) {
            state_[i][0] = initial[i][0] * scale;
            state_[i][1] = initial[i][1] * scale;
        }
    }

    double step(double x) noexcept {
        double value = x;
        for (std::size_t i = 0; i < sections_in_use_; ++i) {
            const SosSection& s = cascade_.sections[i];
            std::array<double, 2>& z = state_[i];
            const double out = s[0] * value + z[0];
            z[0] = s[1] * value - s[4] * out + z[1];
            z[1] = s[2] * value - s[5] * out;
            value = out;
        }
        return value;
    }

    const SosState<MaxSections>& state() const noexcept { return state_; }

private:
    SosCascade<MaxSections> cascade_;
    std::size_t sections_in_use_;
    SosState<MaxSections> state_{};
};

}  // namespace jacobid
