// SPDX-License-Identifier: MIT
// A log header of many columns read into a CsvTable: the name index built once, linear in the columns
// (a header of 400 000 columns was once checked for duplicates pairwise: minutes). The timing that
// tests/integration/cli/test_cli_bad_headers.cpp (WideHeaderIsReadInLinearTime) no longer asserts: that
// test bounds the CPU time of the command line instead.
//
//   build/benchmarks/bench_csv_header
#include <benchmark/benchmark.h>

#include <string>

#include "io/csv_table.hpp"

namespace {

void BM_WideHeader(benchmark::State& state) {
    const auto columns = static_cast<int>(state.range(0));
    std::string text = "t", row = "0";
    for (int c = 0; c < columns; ++c) {
        text += ",x" + std::to_string(c);
        row += ",0";
    }
    text += "\n" + row + "\n";
    for (auto _ : state) {
        const auto table = jacobid::io::parse_csv(text, "wide.csv");
        benchmark::DoNotOptimize(table.columns());
    }
    state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_WideHeader)->RangeMultiplier(4)->Range(1 << 12, 1 << 20)->Unit(benchmark::kMillisecond)->Complexity();

}  // namespace

BENCHMARK_MAIN();
