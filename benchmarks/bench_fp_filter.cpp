// SPDX-License-Identifier: MIT
// The pipeline's decimation filter F_p (zero-phase order-4 Butterworth) over many regressor columns of one
// chunk, side by side: one column at a time through jacobid::sosfiltfilt (the pipeline before issue 18) and
// kFiltfiltLanes (32) columns at once through signal::InterleavedFiltfilt (now). Shapes of the PUMA 560 hour: F_p 8.85 Hz at
// 1 kHz, a chunk of 65 536 samples plus 2 x 1 808 margin; 64 columns (the pipeline filters ~170 non-zero
// ones of 318 per chunk). docs/performance.md, "Several logs, threads and the CSV reader".
//
//   build/benchmarks/bench_fp_filter --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "jacobid/baseline/filtfilt.hpp"
#include "signal/baseline_response.hpp"
#include "signal/interleaved_filtfilt.hpp"

namespace {

constexpr std::size_t kColumns = 64, kSamples = 65'536 + 2 * 1'808;

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

}  // namespace

BENCHMARK_MAIN();
