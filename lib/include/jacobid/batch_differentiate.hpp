// SPDX-License-Identifier: MIT
#pragma once
// Differentiation of a whole recorded signal with one kernel ("valid" correlation): an output exists
// only where the whole window lies inside the record, so the h samples at either end are dropped, never
// invented. Output j is the estimate at input index j + offset_samples() (fractional for most xi != 0).
//
// This is the direct path: O(L) per output, register-blocked so that each weight load feeds a block of
// outputs. Long kernels are faster through the FFT (overlap-save) path of the host library.
#include <cstddef>

#include "jacobid/span.hpp"

namespace jacobid {

enum class BatchStatus {
    Ok,
    EmptyKernel,
    SignalShorterThanWindow,  // fewer samples than taps: not a single complete window
    OutputTooSmall,           // y must hold x.size() - taps + 1 values
};

inline const char* describe(BatchStatus s) noexcept {
    switch (s) {
        case BatchStatus::Ok: return "ok";
        case BatchStatus::EmptyKernel: return "the kernel has no taps";
        case BatchStatus::SignalShorterThanWindow: return "the signal is shorter than the differentiator window";
        case BatchStatus::OutputTooSmall: return "the output buffer is smaller than signal length - taps + 1";
    }
    return "unknown batch status";
}

// Number of outputs of a valid correlation.
inline std::size_t batch_output_size(std::size_t signal_size, std::size_t taps) noexcept {
    return (taps == 0 || signal_size < taps) ? 0 : signal_size - taps + 1;
}

// Input index (possibly fractional) that output 0 refers to: (L - 1)(1 + xi) / 2.
inline double batch_offset_samples(std::size_t taps, double xi) noexcept {
    return 0.5 * static_cast<double>(taps - 1) * (1.0 + xi);
}

// y[j] = sum_k w[k] x[j + k], weights oldest first.
template <typename Scalar>
BatchStatus differentiate_direct(Span<const Scalar> weights, Span<const Scalar> x, Span<Scalar> y) noexcept {
    const std::size_t taps = weights.size();
    if (taps == 0) return BatchStatus::EmptyKernel;
    if (x.size() < taps) return BatchStatus::SignalShorterThanWindow;
    const std::size_t outputs = batch_output_size(x.size(), taps);
    if (y.size() < outputs) return BatchStatus::OutputTooSmall;
    // Blocks of kBlock outputs: the inner loop over the block is independent per output (vectorizable
    // without reassociation), and every weight is loaded once per block instead of once per output.
    // 256 bytes of accumulators (32 doubles: 4 AVX-512, 8 AVX or 16 SSE registers) give enough independent
    // FMA chains to hide their latency; 128 bytes left AVX-512 with 2 chains, 4x slower (docs/performance.md).
    // Each output still sums its taps in order k = 0..L-1, so the block size does not change the rounding.
    constexpr std::size_t kBlock = 256 / sizeof(Scalar);
    const Scalar* w = weights.data();
    const Scalar* in = x.data();
    std::size_t j = 0;
    for (; j + kBlock <= outputs; j += kBlock) {
        Scalar acc[kBlock] = {};
        for (std::size_t k = 0; k < taps; ++k) {
            const Scalar c = w[k];
            const Scalar* src = in + j + k;
            for (std::size_t b = 0; b < kBlock; ++b) acc[b] += c * src[b];
        }
        for (std::size_t b = 0; b < kBlock; ++b) y[j + b] = acc[b];
    }
    for (; j < outputs; ++j) {
        Scalar acc = 0;
        for (std::size_t k = 0; k < taps; ++k) acc += w[k] * in[j + k];
        y[j] = acc;
    }
    return BatchStatus::Ok;
}

}  // namespace jacobid
