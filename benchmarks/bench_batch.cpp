// SPDX-License-Identifier: MIT
// Batch differentiation of a whole record: direct path (lib/), FFT overlap-save path (host-tools,
// FFTW3), their crossover, the FFT block size, FFTW planning (ESTIMATE vs MEASURE) and FFTW vs Eigen's
// unsupported FFT module (kissfft backend).
//
//   bench_batch [google benchmark flags]
//   bench_batch --compare=X.bin --taps=L --out=PREFIX [--repeat=R]
//       one-shot runs on the float64 record X.bin (written by benchmarks/batch_vs_scipy.py): designs the
//       velocity kernel with L taps (kappa = mu = 6, q = 2, Ts = 1 ms, central), writes its weights to
//       PREFIX.w.bin and the differentiate_batch output to PREFIX.y.bin, prints one JSON line of timings
//       (median of R runs; FFT timings include planning and allocation).
#include <benchmark/benchmark.h>
#include <fftw3.h>

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "jacobid/batch_differentiate.hpp"
#include "jacobid/kernel_design.hpp"
#include "signal/fft_convolver.hpp"

namespace {

using jacobid::Span;
using jacobid::signal::FftConvolver;
using jacobid::signal::FftPlanning;

constexpr std::size_t kSignal = std::size_t{1} << 20;  // samples per benchmark iteration

std::vector<double> random_vector(std::size_t n, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<double> v(n);
    for (auto& e : v) e = g(rng);
    return v;
}

// The velocity kernel of the settings, with `taps` taps.
std::vector<double> velocity_kernel(std::size_t taps) {
    jacobid::KernelParams p;
    p.order = 1;
    p.kappa = 6.0;
    p.mu = 6.0;
    p.q = 2;
    p.sample_period = 1e-3;
    p.window = static_cast<double>(taps - 1) * p.sample_period;
    p.xi = 0.0;
    std::vector<double> w(taps);
    if (jacobid::design_kernel(p, Span<double>(w)) != jacobid::KernelStatus::Ok) std::abort();
    return w;
}

const std::vector<double>& signal() {
    static const std::vector<double> x = random_vector(kSignal, 1);
    return x;
}

void set_rate(benchmark::State& state) {
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kSignal));  // input samples / s
}

void BM_Direct(benchmark::State& state) {
    const auto taps = static_cast<std::size_t>(state.range(0));
    const std::vector<double> w = velocity_kernel(taps);
    const std::vector<double>& x = signal();
    std::vector<double> y(jacobid::batch_output_size(x.size(), taps));
    for (auto _ : state) {
        jacobid::differentiate_direct(Span<const double>(w), Span<const double>(x), Span<double>(y));
        benchmark::DoNotOptimize(y.data());
        benchmark::ClobberMemory();
    }
    set_rate(state);
}

// Planned once outside the loop: the steady-state cost of the FFT path.
void BM_Fft(benchmark::State& state) {
    const auto taps = static_cast<std::size_t>(state.range(0));
    const auto fft_size = static_cast<std::size_t>(state.range(1));
    const std::vector<double> w = velocity_kernel(taps);
    const std::vector<double>& x = signal();
    std::vector<double> y(jacobid::batch_output_size(x.size(), taps));
    const FftConvolver conv(Span<const double>(w), fft_size);
    for (auto _ : state) {
        conv.correlate(Span<const double>(x), Span<double>(y));
        benchmark::DoNotOptimize(y.data());
        benchmark::ClobberMemory();
    }
    state.counters["fft_size"] = static_cast<double>(conv.fft_size());
    set_rate(state);
}

// Planning cost of one FftConvolver (two 1-D real plans + the kernel spectrum). FFTW accumulates wisdom
// across plans in a process; with range(2) != 0 it is forgotten before each plan, so every iteration
// plans from scratch as the first plan of a process does; otherwise later plans reuse it.
void BM_FftPlan(benchmark::State& state) {
    const auto fft_size = static_cast<std::size_t>(state.range(0));
    const FftPlanning planning = state.range(1) != 0 ? FftPlanning::Measure : FftPlanning::Estimate;
    const bool forget = state.range(2) != 0;
    const std::vector<double> w = velocity_kernel(211);
    for (auto _ : state) {
        if (forget) fftw_forget_wisdom();
        const FftConvolver conv(Span<const double>(w), fft_size, planning);
        benchmark::DoNotOptimize(conv.fft_size());
    }
    state.SetLabel(std::string(planning == FftPlanning::Measure ? "FFTW_MEASURE" : "FFTW_ESTIMATE") +
                   (forget ? ", from scratch" : ", wisdom kept"));
}

// Steady-state cost with MEASURE plans, to set against BM_Fft (ESTIMATE).
void BM_FftMeasured(benchmark::State& state) {
    const auto taps = static_cast<std::size_t>(state.range(0));
    const std::vector<double> w = velocity_kernel(taps);
    const std::vector<double>& x = signal();
    std::vector<double> y(jacobid::batch_output_size(x.size(), taps));
    fftw_forget_wisdom();
    const FftConvolver conv(Span<const double>(w), 0, FftPlanning::Measure);
    for (auto _ : state) {
        conv.correlate(Span<const double>(x), Span<double>(y));
        benchmark::DoNotOptimize(y.data());
        benchmark::ClobberMemory();
    }
    set_rate(state);
}

// Real forward + inverse transform of size N: FFTW3 (ESTIMATE plan, as the convolver uses) ...
void BM_FftwRoundTrip(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    auto* real = static_cast<double*>(fftw_malloc(sizeof(double) * n));
    auto* freq = static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * (n / 2 + 1)));
    const fftw_plan fwd = fftw_plan_dft_r2c_1d(static_cast<int>(n), real, freq, FFTW_ESTIMATE);
    const fftw_plan inv = fftw_plan_dft_c2r_1d(static_cast<int>(n), freq, real, FFTW_ESTIMATE);
    const std::vector<double> x = random_vector(n, 2);
    std::copy(x.begin(), x.end(), real);
    for (auto _ : state) {
        fftw_execute(fwd);
        fftw_execute(inv);
        benchmark::DoNotOptimize(real);
        benchmark::ClobberMemory();
    }
    fftw_destroy_plan(fwd);
    fftw_destroy_plan(inv);
    fftw_free(real);
    fftw_free(freq);
}

// ... and Eigen's unsupported FFT module with its default kissfft backend (half spectrum, real input).
void BM_KissRoundTrip(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    Eigen::FFT<double> fft;
    fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
    fft.SetFlag(Eigen::FFT<double>::Unscaled);
    std::vector<double> real = random_vector(n, 2);
    std::vector<std::complex<double>> freq;
    for (auto _ : state) {
        fft.fwd(freq, real);
        fft.inv(real, freq);
        benchmark::DoNotOptimize(real.data());
        benchmark::ClobberMemory();
    }
}

void register_benchmarks() {
    const std::vector<long> taps = {8, 16, 24, 32, 48, 64, 96, 128, 211, 401, 1101};
    for (long t : taps) benchmark::RegisterBenchmark("batch/direct", BM_Direct)->Arg(t)->Unit(benchmark::kMillisecond);
    for (long t : taps) benchmark::RegisterBenchmark("batch/fft", BM_Fft)->Args({t, 0})->Unit(benchmark::kMillisecond);
    // Block size sweep around the default (the power of two nearest to 8 L).
    for (long t : {211L, 1101L}) {
        for (long n = 512; n <= 65536; n *= 2) {
            if (n >= t) benchmark::RegisterBenchmark("fft_block_size", BM_Fft)->Args({t, n})->Unit(benchmark::kMillisecond);
        }
    }
    for (long t : {211L, 1101L}) benchmark::RegisterBenchmark("batch/fft_measure", BM_FftMeasured)->Arg(t)->Unit(benchmark::kMillisecond);
    for (long n : {2048L, 8192L}) {
        benchmark::RegisterBenchmark("fft_plan", BM_FftPlan)->Args({n, 0, 1})->Unit(benchmark::kMicrosecond);
        benchmark::RegisterBenchmark("fft_plan", BM_FftPlan)->Args({n, 0, 0})->Unit(benchmark::kMicrosecond);
        benchmark::RegisterBenchmark("fft_plan", BM_FftPlan)->Args({n, 1, 1})->Unit(benchmark::kMicrosecond)->Iterations(3);
    }
    for (long n : {2048L, 8192L}) {
        benchmark::RegisterBenchmark("roundtrip/fftw", BM_FftwRoundTrip)->Arg(n)->Unit(benchmark::kMicrosecond);
        benchmark::RegisterBenchmark("roundtrip/kissfft", BM_KissRoundTrip)->Arg(n)->Unit(benchmark::kMicrosecond);
    }
}

// ---- --compare: one-shot runs for batch_vs_scipy.py ----------------------------------------------------

template <typename F>
double median_seconds(int repeat, F&& f) {
    std::vector<double> t;
    for (int r = 0; r < repeat; ++r) {
        const auto start = std::chrono::steady_clock::now();
        f();
        t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

std::vector<double> read_doubles(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) {
        std::fprintf(stderr, "cannot read %s\n", path.c_str());
        std::exit(2);
    }
    std::vector<double> v(static_cast<std::size_t>(in.tellg()) / sizeof(double));
    in.seekg(0);
    in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(double)));
    return v;
}

void write_doubles(const std::string& path, const std::vector<double>& v) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(double)));
}

int compare(const std::string& x_path, std::size_t taps, const std::string& prefix, int repeat) {
    const std::vector<double> x = read_doubles(x_path);
    const std::vector<double> w = velocity_kernel(taps);
    const Span<const double> ws(w), xs(x);
    const std::size_t outputs = jacobid::batch_output_size(x.size(), taps);
    std::vector<double> direct(outputs), fft(outputs), batch(outputs);

    const double t_direct = median_seconds(repeat, [&] { jacobid::differentiate_direct(ws, xs, Span<double>(direct)); });
    const double t_estimate = median_seconds(repeat, [&] { FftConvolver(ws, 0, FftPlanning::Estimate).correlate(xs, Span<double>(fft)); });
    double t_plan = 0;
    const double t_measure = median_seconds(repeat, [&] {
        fftw_forget_wisdom();  // no help from the previous repetition's plans
        const auto start = std::chrono::steady_clock::now();
        const FftConvolver conv(ws, 0, FftPlanning::Measure);
        t_plan = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        conv.correlate(xs, Span<double>(fft));
    });
    const double t_batch = median_seconds(repeat, [&] { jacobid::signal::differentiate_batch(ws, xs, Span<double>(batch)); });

    // FFT vs direct, relative to sum|w| max|x|.
    double max_diff = 0, x_max = 0, w_sum = 0;
    for (std::size_t j = 0; j < outputs; ++j) max_diff = std::max(max_diff, std::abs(fft[j] - direct[j]));
    for (double v : x) x_max = std::max(x_max, std::abs(v));
    for (double v : w) w_sum += std::abs(v);

    write_doubles(prefix + ".w.bin", w);
    write_doubles(prefix + ".y.bin", batch);
    std::printf(
        "{\"taps\": %zu, \"samples\": %zu, \"direct_s\": %.6f, \"fft_estimate_s\": %.6f, \"fft_measure_s\": %.6f, "
        "\"fft_measure_plan_s\": %.6f, \"batch_s\": %.6f, \"fft_size\": %zu, \"fft_vs_direct_rel\": %.3e}\n",
        taps, x.size(), t_direct, t_estimate, t_measure, t_plan, t_batch, FftConvolver::default_fft_size(taps),
        max_diff / (w_sum * x_max));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    std::string x_path, prefix;
    std::size_t taps = 211;
    int repeat = 3;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.rfind("--compare=", 0) == 0) x_path = arg.substr(10);
        if (arg.rfind("--taps=", 0) == 0) taps = std::strtoull(arg.c_str() + 7, nullptr, 10);
        if (arg.rfind("--out=", 0) == 0) prefix = arg.substr(6);
        if (arg.rfind("--repeat=", 0) == 0) repeat = std::atoi(arg.c_str() + 9);
    }
    if (!x_path.empty()) return compare(x_path, taps, prefix.empty() ? std::string("batch") : prefix, std::max(repeat, 1));
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    register_benchmarks();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
