// SPDX-License-Identifier: MIT
// The pipeline's decimation filter F_p (zero-phase order-4 Butterworth) over many regressor columns of one
// chunk, side by side: one column at a time through jacobid::sosfiltfilt (the pipeline before issue 18) and
// kFiltfiltLanes (32) columns at once through signal::InterleavedFiltfilt (now). Shapes of the PUMA 560 hour: F_p 8.85 Hz at
// 1 kHz, a chunk of 65 536 samples plus 2 x 1 808 margin; 64 columns (the pipeline filters ~170 non-zero
// ones of 318 per chunk). docs/performance.md, "Several logs, threads and the CSV reader".
//
// Third, the scheme issue 18 asked to weigh: a decimating FIR with F_p's zero-phase response, evaluated only at
// the samples the decimation keeps (1 in 28 for the hour). filtfilt's response is the symmetric impulse
// response h = g * g(-t) of the cascade g, infinite but decaying; truncated where |h| falls below 1e-12 of its
// peak (the 1e-9 to which identification results must agree leaves room), it has 2 x 1 263 + 1 taps for
// F_p at 8.85 Hz, and each kept sample costs 1 264 multiplications and 2 526 additions (symmetric taps folded),
// i.e. 45 + 90 per input sample, against 20 + 16 for the two passes of two biquads at the full rate. The check
// below holds the truncated FIR to sosfiltfilt at every kept sample of the chunk's interior before timing it.
//
//   build/benchmarks/bench_fp_filter --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "jacobid/baseline/filtfilt.hpp"
#include "signal/baseline_response.hpp"
#include "signal/interleaved_filtfilt.hpp"

namespace {

constexpr std::size_t kColumns = 64, kMargin = 1'808, kSamples = 65'536 + 2 * kMargin;
constexpr std::size_t kDecimation = 28;  // the PUMA hour's
constexpr double kTapTolerance = 1e-12;  // taps below this fraction of the peak are dropped

struct Chunk {
    jacobid::signal::ButterworthSos fp = jacobid::signal::design_butterworth_or_throw(4, 8.85, 1e-3, "F_p");
    std::vector<std::vector<double>> columns;
    Chunk() {
        std::mt19937 rng(1);
        std::normal_distribution<double> noise(0.0, 1.0);
        columns.assign(kColumns, std::vector<double>(kSamples));
        for (std::size_t c = 0; c < kColumns; ++c) {
            for (std::size_t k = 0; k < kSamples; ++k) columns[c][k] = std::sin(1e-3 * static_cast<double>(k * (c + 1))) + 0.1 * noise(rng);
        }
    }
};

const Chunk& chunk() {
    static const Chunk c;
    return c;
}

void BM_FpOneColumnAtATime(benchmark::State& state) {
    const Chunk& c = chunk();
    std::vector<std::vector<double>> work = c.columns;
    std::vector<double> workspace(jacobid::sosfiltfilt_workspace_size(c.fp));
    for (auto _ : state) {
        for (auto& column : work) {
            jacobid::sosfiltfilt(c.fp, jacobid::Span<const double>(column), jacobid::Span<double>(column), jacobid::Span<double>(workspace));
        }
        benchmark::DoNotOptimize(work.front().data());
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kColumns * kSamples));
}
BENCHMARK(BM_FpOneColumnAtATime)->Unit(benchmark::kMillisecond);

void BM_FpInterleaved(benchmark::State& state) {
    const Chunk& c = chunk();
    std::vector<std::vector<double>> work = c.columns;
    jacobid::signal::InterleavedFiltfilt filter(c.fp);
    std::vector<double*> pointers;
    for (auto& column : work) pointers.push_back(column.data());
    for (auto _ : state) {
        for (std::size_t first = 0; first < kColumns; first += jacobid::signal::kFiltfiltLanes) {
            filter.filter_in_place(pointers.data() + first, jacobid::signal::kFiltfiltLanes, kSamples);
        }
        benchmark::DoNotOptimize(work.front().data());
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kColumns * kSamples));
}
BENCHMARK(BM_FpInterleaved)->Unit(benchmark::kMillisecond);

// F_p's zero-phase impulse response: sosfiltfilt of a unit impulse far from both ends (edge effects there are
// below 1e-20), kept from the centre out while it is above kTapTolerance of its peak. half_taps[d] = h[d].
std::vector<double> zero_phase_half_taps(const jacobid::signal::ButterworthSos& fp) {
    const std::size_t n = 2 * 4'096 + 1, centre = n / 2;
    std::vector<double> impulse(n, 0.0), response(n);
    impulse[centre] = 1.0;
    std::vector<double> workspace(jacobid::sosfiltfilt_workspace_size(fp));
    jacobid::sosfiltfilt(fp, jacobid::Span<const double>(impulse), jacobid::Span<double>(response), jacobid::Span<double>(workspace));
    const double peak = std::abs(response[centre]);
    std::size_t half = 0;
    for (std::size_t d = 1; d < centre; ++d) {
        if (std::abs(response[centre + d]) > kTapTolerance * peak) half = d;
    }
    return std::vector<double>(response.begin() + static_cast<std::ptrdiff_t>(centre), response.begin() + static_cast<std::ptrdiff_t>(centre + half + 1));
}

// The kept samples of kFiltfiltLanes columns at once, interleaved (sample-major) so that the lanes, not a
// reduction, are what the compiler vectorizes; out[i * lanes + l] is column l at sample kMargin + i * kDecimation.
void decimating_fir(const std::vector<double>& half_taps, const std::vector<double>& interleaved, std::vector<double>& out) {
    constexpr std::size_t lanes = jacobid::signal::kFiltfiltLanes;
    const std::size_t half = half_taps.size() - 1;
    std::size_t i = 0;
    for (std::size_t k = kMargin; k < kSamples - kMargin; k += kDecimation, ++i) {
        double acc[lanes];
        const double* centre = interleaved.data() + k * lanes;
        for (std::size_t l = 0; l < lanes; ++l) acc[l] = half_taps[0] * centre[l];
        for (std::size_t d = 1; d <= half; ++d) {
            const double* before = centre - d * lanes;
            const double* after = centre + d * lanes;
            for (std::size_t l = 0; l < lanes; ++l) acc[l] += half_taps[d] * (before[l] + after[l]);
        }
        std::copy(acc, acc + lanes, out.data() + i * lanes);
    }
}

void interleave(const std::vector<std::vector<double>>& columns, std::size_t first, std::vector<double>& interleaved) {
    constexpr std::size_t lanes = jacobid::signal::kFiltfiltLanes;
    for (std::size_t k = 0; k < kSamples; ++k) {
        for (std::size_t l = 0; l < lanes; ++l) interleaved[k * lanes + l] = columns[first + l][k];
    }
}

void BM_FpDecimatingFir(benchmark::State& state) {
    const Chunk& c = chunk();
    const std::vector<double> half_taps = zero_phase_half_taps(c.fp);
    if (half_taps.size() - 1 > kMargin) {
        state.SkipWithError("F_p's truncated response is longer than the chunk's margin");
        return;
    }
    constexpr std::size_t lanes = jacobid::signal::kFiltfiltLanes;
    const std::size_t kept = (kSamples - 2 * kMargin + kDecimation - 1) / kDecimation;
    std::vector<double> interleaved(kSamples * lanes), out(kept * lanes);
    {
        // Against today's filter: every kept sample of the first lanes columns equals sosfiltfilt's.
        interleave(c.columns, 0, interleaved);
        decimating_fir(half_taps, interleaved, out);
        std::vector<double> filtered(kSamples), workspace(jacobid::sosfiltfilt_workspace_size(c.fp));
        double worst = 0.0;
        for (std::size_t l = 0; l < lanes; ++l) {
            jacobid::sosfiltfilt(c.fp, jacobid::Span<const double>(c.columns[l]), jacobid::Span<double>(filtered), jacobid::Span<double>(workspace));
            for (std::size_t i = 0; i < kept; ++i) worst = std::max(worst, std::abs(out[i * lanes + l] - filtered[kMargin + i * kDecimation]));
        }
        state.counters["max_abs_error"] = worst;  // the columns are of order 1
        if (!(worst < 1e-10)) {
            state.SkipWithError("the decimating FIR differs from sosfiltfilt at the kept samples");
            return;
        }
    }
    for (auto _ : state) {
        for (std::size_t first = 0; first < kColumns; first += lanes) {
            interleave(c.columns, first, interleaved);
            decimating_fir(half_taps, interleaved, out);
            benchmark::DoNotOptimize(out.data());
        }
    }
    state.counters["taps"] = static_cast<double>(2 * half_taps.size() - 1);
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kColumns * kSamples));
}
BENCHMARK(BM_FpDecimatingFir)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
