// SPDX-License-Identifier: MIT
#pragma once
// Batch differentiation of long records through the FFT (FFTW3 real-to-complex overlap-save).
//
// FftConvolver computes exactly what jacobid::differentiate_direct computes (lib/include/jacobid/
// batch_differentiate.hpp): the "valid" correlation y[j] = sum_k w[k] x[j + k], weights oldest first,
// x.size() - taps + 1 outputs, and the same BatchStatus errors. Only the rounding differs (FFT error is
// of the order of eps * log2(N) * sum|w||x|).
//
// Overlap-save: correlation with w is convolution with the reversed kernel h[m] = w[L-1-m]. A block of N
// input samples x[s .. s+N) is transformed, multiplied by the spectrum of h (zero-padded to N) and
// transformed back; of the N circular-convolution outputs the last N - L + 1 are free of wrap-around and
// are y[s .. s+N-L]. Consecutive blocks therefore overlap by L - 1 samples and advance by N - L + 1.
//
// Block size (fft_size N): the power of two nearest to 8 L (see default_fft_size). The cost per output is
// about (two real FFTs of N + N/2 complex products) / (N - L + 1): with N = 2L half of every FFT is thrown
// away; beyond ~8L the log2(N) growth of the FFT cost outweighs the shrinking overlap, and the working set
// (about 24 N bytes) leaves the L1/L2 caches. Measured (docs/performance.md, "FFT block size"): 2048-4096
// is best for L = 211 (8L = 1688), 4096-8192 for L = 1101 (8L = 8808); the rule is within 5 % of the best
// in both builds, while the next power of two above 8L (16384 for 1101 taps) is 10-11 % slower than the best.
//
// Host side only: FFTW3 is GPL-2+, the real-time core (lib/) never links it.
#include <cstddef>
#include <memory>

#include "jacobid/batch_differentiate.hpp"
#include "jacobid/span.hpp"

namespace jacobid::signal {

// How FFTW chooses its algorithm. Estimate plans from heuristics (~50-200 us per convolver here, ~2 ms for
// the first plan of a process); Measure times candidate algorithms (0.3-0.6 s per convolver here) for
// transforms at most ~6 % faster. For a one-shot 1e7-sample run Estimate is far faster overall
// (docs/performance.md, "FFTW planning"); Measure pays off only for a convolver reused over ~1e9 samples.
enum class FftPlanning { Estimate, Measure };

class FftConvolver {
public:
    // Plans the transforms for `weights` (copied) and a block of `fft_size` samples (0: default_fft_size).
    // An fft_size smaller than the kernel is raised to default_fft_size. Empty weights give a
    // convolver whose correlate() returns EmptyKernel. Plan creation is serialized internally (FFTW's
    // planner is not thread-safe); correlate() may run concurrently on one convolver.
    explicit FftConvolver(Span<const double> weights, std::size_t fft_size = 0, FftPlanning planning = FftPlanning::Estimate);
    ~FftConvolver();
    FftConvolver(FftConvolver&&) noexcept;
    FftConvolver& operator=(FftConvolver&&) noexcept;
    FftConvolver(const FftConvolver&) = delete;
    FftConvolver& operator=(const FftConvolver&) = delete;

    // y[j] = sum_k w[k] x[j + k] for j < x.size() - taps + 1; same statuses as differentiate_direct.
    BatchStatus correlate(Span<const double> x, Span<double> y) const;

    std::size_t taps() const noexcept;
    std::size_t fft_size() const noexcept;
    // Outputs produced per FFT block: fft_size - taps + 1.
    std::size_t block_outputs() const noexcept;

    // The power of two nearest to 8 * taps on a log scale (the smallest one >= 8 taps / sqrt(2)), at least 64.
    static std::size_t default_fft_size(std::size_t taps) noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Kernel length from which differentiate_batch uses the FFT path: the measured crossover of the direct path
// (whose speed depends on the SIMD width this file is compiled for) and the FFT path (FFTW picks its own
// SIMD code at run time), docs/performance.md "Direct vs FFT crossover". -march=native on the AVX-512
// machine: equal between 64 and 96 taps (FFT 17 % faster at 96); default x86-64 flags (SSE2, no FMA): equal
// at ~32 taps. AVX2-only builds were not measured; they get the lower value.
#if defined(__AVX512F__)
constexpr std::size_t kFftCrossoverTaps = 96;
#else
constexpr std::size_t kFftCrossoverTaps = 32;
#endif
// Below this many multiply-adds (outputs x taps) the direct path is used whatever the kernel length: an
// FFTW_ESTIMATE plan costs ~50 us once the planner is warm (~2 ms for the first plan of a process), the
// time of ~1e6 direct multiply-adds.
constexpr std::size_t kFftMinimumWork = std::size_t{1} << 20;

// Valid correlation of a whole record, by the direct path for short kernels or small jobs and by the FFT
// path (FftPlanning::Estimate, default block size) otherwise. Same contract as differentiate_direct.
BatchStatus differentiate_batch(Span<const double> weights, Span<const double> x, Span<double> y);

}  // namespace jacobid::signal
