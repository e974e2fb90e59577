// SPDX-License-Identifier: MIT
#pragma once
// Dot product of two contiguous arrays with independent partial sums. A plain `s += a[i] * b[i]` loop is
// a serial dependency chain the compiler may not reorder (no -ffast-math in the core); keeping Lanes
// separate accumulators lets it use full SIMD registers while staying deterministic.
#include <cstddef>

namespace jacobid {

template <typename Scalar>
inline Scalar dot_product(const Scalar* a, const Scalar* b, std::size_t n) noexcept {
    // 128 bytes of partial sums (16 doubles, 32 floats): four AVX or eight SSE registers, enough
    // independent chains to hide the add latency behind the loads.
    constexpr std::size_t kLanes = 128 / sizeof(Scalar);
    Scalar acc[kLanes] = {};
    std::size_t i = 0;
    for (; i + kLanes <= n; i += kLanes) {
        for (std::size_t l = 0; l < kLanes; ++l) acc[l] += a[i + l] * b[i + l];
    }
    Scalar tail = 0;
    for (; i < n; ++i) tail += a[i] * b[i];
    // Pairwise reduction of the lanes.
    for (std::size_t width = kLanes / 2; width > 0; width /= 2) {
        for (std::size_t l = 0; l < width; ++l) acc[l] += acc[l + width];
    }
    return acc[0] + tail;
}

}  // namespace jacobid
