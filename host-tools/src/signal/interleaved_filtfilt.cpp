// SPDX-License-Identifier: MIT
#include "signal/interleaved_filtfilt.hpp"

#include <fmt/core.h>

#include <array>

#include "core/errors.hpp"
#include "jacobid/baseline/filtfilt.hpp"

namespace jacobid::signal {
namespace {

using LaneValues = std::array<double, kFiltfiltLanes>;

// One step of every section for every lane: SosFilterState::step's arithmetic, lane by lane.
struct LaneStates {
    std::array<LaneValues, kMaxButterworthSections> z0{}, z1{};
};

inline void reset_lanes(LaneStates& state, const SosState<kMaxButterworthSections>& initial, std::size_t sections, const double* scale) {
    for (std::size_t s = 0; s < sections; ++s) {
        for (std::size_t l = 0; l < kFiltfiltLanes; ++l) {
            state.z0[s][l] = initial[s][0] * scale[l];
            state.z1[s][l] = initial[s][1] * scale[l];
        }
    }
}

inline void step_lanes(LaneStates& state, const ButterworthSos& cascade, std::size_t sections, double* row) {
    LaneValues value;
    for (std::size_t l = 0; l < kFiltfiltLanes; ++l) value[l] = row[l];
    for (std::size_t s = 0; s < sections; ++s) {
        const SosSection& c = cascade.sections[s];
        const double b0 = c[0], b1 = c[1], b2 = c[2], a1 = c[4], a2 = c[5];
        LaneValues& z0 = state.z0[s];
        LaneValues& z1 = state.z1[s];
        for (std::size_t l = 0; l < kFiltfiltLanes; ++l) {
            const double out = b0 * value[l] + z0[l];
            z0[l] = b1 * value[l] - a1 * out + z1[l];
            z1[l] = b2 * value[l] - a2 * out;
            value[l] = out;
        }
    }
    for (std::size_t l = 0; l < kFiltfiltLanes; ++l) row[l] = value[l];
}

}  // namespace

InterleavedFiltfilt::InterleavedFiltfilt(const ButterworthSos& cascade) : cascade_(cascade) {
    if (validate_cascade(cascade_) != FilterStatus::Ok) throw InputError("interleaved zero-phase filter: malformed second-order sections");
    steady_state_ = sosfilt_zi(cascade_);
    padlen_ = sosfiltfilt_padlen(cascade_);
}

void InterleavedFiltfilt::filter_in_place(double* const* signals, std::size_t count, std::size_t n) {
    if (count == 0 || count > kFiltfiltLanes) throw InputError(fmt::format("interleaved zero-phase filter: {} signals (1 to {})", count, kFiltfiltLanes));
    if (n <= padlen_) throw InputError(fmt::format("zero-phase filter on {} samples: {}", n, describe(FilterStatus::SignalTooShort)));
    const std::size_t p = padlen_, rows = p + n + p;
    data_.resize(rows * kFiltfiltLanes);
    double* d = data_.data();
    // Lanes beyond `count` repeat the last signal: the same work, results discarded.
    std::array<const double*, kFiltfiltLanes> x{};
    for (std::size_t l = 0; l < kFiltfiltLanes; ++l) x[l] = signals[l < count ? l : count - 1];
    // [left | x | right] with sosfiltfilt's point reflections: left[i] = 2 x[0] - x[p - i],
    // right[i] = 2 x[n - 1] - x[n - 2 - i].
    for (std::size_t i = 0; i < p; ++i) {
        for (std::size_t l = 0; l < kFiltfiltLanes; ++l) {
            d[i * kFiltfiltLanes + l] = 2.0 * x[l][0] - x[l][p - i];
            d[(p + n + i) * kFiltfiltLanes + l] = 2.0 * x[l][n - 1] - x[l][n - 2 - i];
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t l = 0; l < kFiltfiltLanes; ++l) d[(p + i) * kFiltfiltLanes + l] = x[l][i];
    }
    const std::size_t sections = cascade_.count < kMaxButterworthSections ? cascade_.count : kMaxButterworthSections;
    LaneStates state;
    // Forward from the steady state of the first extended sample, over all rows.
    reset_lanes(state, steady_state_, sections, d);
    for (std::size_t r = 0; r < rows; ++r) step_lanes(state, cascade_, sections, d + r * kFiltfiltLanes);
    // Backward from the steady state of the last forward output; the left extension's backward outputs
    // would be dropped, so the pass stops at the first sample of x.
    reset_lanes(state, steady_state_, sections, d + (rows - 1) * kFiltfiltLanes);
    for (std::size_t r = rows; r-- > p;) step_lanes(state, cascade_, sections, d + r * kFiltfiltLanes);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t l = 0; l < count; ++l) signals[l][i] = d[(p + i) * kFiltfiltLanes + l];
    }
}

}  // namespace jacobid::signal
