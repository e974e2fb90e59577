// SPDX-License-Identifier: MIT
#pragma once
// Zero-phase forward-backward filtering (jacobid::sosfiltfilt, scipy.signal.sosfiltfilt's edges) of up to
// kFiltfiltLanes signals at once. An IIR recursion is latency-bound: each output waits for the previous
// one, so one signal at a time leaves the FPU mostly idle. Interleaving independent signals (sample-major,
// one lane per signal) lets the recursions of all lanes advance in one vectorized loop. Every lane goes
// through the same operations in the same order as the one-signal filter, so each signal's result is that
// of sosfiltfilt up to how the compiler contracts products and sums into fused multiply-adds in the two
// loops (test: within 4e-16 of the signal's magnitude; the PUMA hour's identification came out the same bit for
// bit with -march=native); the pipeline's F_p (6 x 52 regressor columns on a PUMA) is where this matters.
#include <cstddef>
#include <vector>

#include "jacobid/baseline/sos.hpp"
#include "signal/baseline_response.hpp"

namespace jacobid::signal {

// 32: bench_fp_filter measured 16 / 32 / 64 lanes at 17.5 / 14.5 / 22.5 ms for 64 columns of a PUMA chunk
// (64 lanes leave the cache); 16 keeps only two AVX-512 recursions in flight.
inline constexpr std::size_t kFiltfiltLanes = 32;

class InterleavedFiltfilt {
public:
    // Throws InputError when the cascade is malformed (validate_cascade).
    explicit InterleavedFiltfilt(const ButterworthSos& cascade);

    // sosfiltfilt's extension at each end; signals must be longer than this.
    std::size_t padlen() const { return padlen_; }

    // Filters `count` (1 .. kFiltfiltLanes) signals of `n` samples each in place: signals[l][0 .. n).
    // Throws InputError when n <= padlen() (where sosfiltfilt returns SignalTooShort) or count is out of range.
    void filter_in_place(double* const* signals, std::size_t count, std::size_t n);

private:
    ButterworthSos cascade_;
    SosState<kMaxButterworthSections> steady_state_{};
    std::size_t padlen_ = 0;
    std::vector<double> data_;  // the extended signals, (padlen + n + padlen) rows x kFiltfiltLanes, sample-major
};

}  // namespace jacobid::signal
