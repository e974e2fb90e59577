// SPDX-License-Identifier: MIT
// The C++ side of the Python module's cost check (benchmarks/bench_python_module.py, docs/performance.md):
// times signal::jacobi_estimate, the call jacobid.differentiate makes, on a record of --samples samples,
// with the kernel options parsed by the command line's own option code (as the module parses its keywords).
//
//   bench_estimate --samples N --repeat R [kernel options: --window 0.05 --ts 0.001 --order 1 ...]
//
// Prints one JSON line: {"samples": N, "repeat": R, "median_s": ..., "min_s": ...}. The design of the
// kernel is outside the timed region here and inside it in the module (a few microseconds).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "options/kernel_options.hpp"
#include "signal/differentiation.hpp"

int main(int argc, char** argv) {
    CLI::App app("bench_estimate: jacobi_estimate timed on a long record");
    std::size_t samples = 10'000'000;
    int repeat = 7;
    jacobid::options::KernelOptions options;
    app.add_option("--samples", samples, "record length");
    app.add_option("--repeat", repeat, "timed runs (the median is reported)");
    jacobid::options::add_kernel_options(&app, options, true, true);
    CLI11_PARSE(app, argc, argv);

    const jacobid::KernelParams params = jacobid::options::to_kernel_params(options);
    const std::vector<double> weights = jacobid::options::design_kernel_or_throw(params);
    // The same record as the Python side: a 1 Hz sine plus uniform noise (the values do not change the cost).
    std::vector<double> x(samples);
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
    for (std::size_t i = 0; i < samples; ++i) x[i] = std::sin(2.0 * M_PI * 1e-3 * static_cast<double>(i)) + noise(rng);

    std::vector<double> seconds;
    double checksum = 0.0;
    for (int r = 0; r < repeat; ++r) {
        const auto start = std::chrono::steady_clock::now();
        const jacobid::signal::Estimate e = jacobid::signal::jacobi_estimate(params, weights, jacobid::Span<const double>(x.data(), x.size()), "x");
        seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        checksum += e.values.empty() ? 0.0 : e.values[e.values.size() / 2];
    }
    std::sort(seconds.begin(), seconds.end());
    std::printf("{\"samples\": %zu, \"repeat\": %d, \"median_s\": %.6f, \"min_s\": %.6f, \"checksum\": %.9g}\n", samples, repeat,
                seconds[seconds.size() / 2], seconds.front(), checksum);
    return 0;
}
