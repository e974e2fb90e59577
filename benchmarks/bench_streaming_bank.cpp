// SPDX-License-Identifier: MIT
// Streaming tick: 6 joints x (q^, qd^, qdd^), 211 taps each (kappa = mu = 6, q = 2, T = 0.21 s,
// Ts = 1 ms, central), plus the torque delay: jacobid::DifferentiatorBank<Scalar, 6, 256> against a
// straightforward implementation (modulo-indexed ring buffer, plain scalar loop) in the same binary.
//
//   bench_streaming_bank [google benchmark flags]   timings; prints a median summary with the speed-ups
//   bench_streaming_bank --driver=IMPL --ticks=N    N ticks of one implementation and nothing else (for
//                                                   valgrind --tool=callgrind, benchmarks/run_callgrind.sh)
//   bench_streaming_bank --driver=check --ticks=N   both implementations agree (ctest smoke run)
// IMPL: bank_double, bank_float, naive_double, naive_float.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "jacobid/differentiator_bank.hpp"

namespace {

constexpr int kJoints = 6;
constexpr std::size_t kCapacity = 256;
constexpr std::size_t kInputTicks = 1024;  // cycled input table (fits in L1/L2, not a single repeated value)

jacobid::KernelParams params(int order) {
    jacobid::KernelParams p;
    p.order = order;
    p.kappa = 6.0;
    p.mu = 6.0;
    p.q = 2;
    p.window = 0.21;
    p.sample_period = 1e-3;
    p.xi = 0.0;
    return p;
}

std::array<jacobid::JointFilterConfig, kJoints> bank_config() {
    std::array<jacobid::JointFilterConfig, kJoints> config{};
    for (auto& joint : config) {
        for (int c = 0; c < jacobid::kChannelCount; ++c) joint.params[c] = params(c);
    }
    return config;
}

// The straightforward implementation the issue compares against: one ring buffer per joint indexed
// (head + k) % capacity for every tap, and a plain `s += w[k] * x[...]` loop per channel. Capacity is a
// compile-time power of two, as in the bank, so `%` compiles to a mask: the most favourable form of the
// baseline, not a strawman with a division per tap.
template <typename Scalar, int Joints, std::size_t Capacity>
class NaiveBank {
public:
    using Vector = Eigen::Matrix<Scalar, Joints, 1>;

    // Same weights and delays as the bank (all channels share the 105-sample delay here, so no lags).
    template <typename Bank>
    void configure(const Bank& bank) {
        for (int j = 0; j < Joints; ++j) {
            for (int c = 0; c < jacobid::kChannelCount; ++c) {
                const auto w = bank.kernel(j, c).weights();
                weights_[j][c].assign(w.begin(), w.end());
            }
        }
        taps_ = bank.kernel(0, 0).taps();
        delay_ = bank.delay_samples();
    }

    void step(const Vector& position, const Vector& torque, jacobid::BankOutput<Scalar, Joints>& out) {
        for (int j = 0; j < Joints; ++j) {
            positions_[j][head_] = position[j];
            torques_[j][head_] = torque[j];
        }
        head_ = (head_ + 1) % Capacity;
        const std::size_t oldest = head_ + Capacity - taps_;  // window start, before the modulo
        for (int j = 0; j < Joints; ++j) {
            Scalar result[jacobid::kChannelCount];
            for (int c = 0; c < jacobid::kChannelCount; ++c) {
                Scalar s = 0;
                for (std::size_t k = 0; k < taps_; ++k) s += weights_[j][c][k] * positions_[j][(oldest + k) % Capacity];
                result[c] = s;
            }
            out.position[j] = result[jacobid::kPosition];
            out.velocity[j] = result[jacobid::kVelocity];
            out.acceleration[j] = result[jacobid::kAcceleration];
            out.torque[j] = torques_[j][(head_ + Capacity - 1 - delay_) % Capacity];
        }
    }

private:
    std::array<std::array<std::vector<Scalar>, jacobid::kChannelCount>, Joints> weights_{};
    std::array<std::array<Scalar, Capacity>, Joints> positions_{};
    std::array<std::array<Scalar, Capacity>, Joints> torques_{};
    std::size_t head_ = 0;
    std::size_t taps_ = 0;
    std::size_t delay_ = 0;
};

// Joint positions and torques: a few sines per joint, sampled at 1 kHz.
template <typename Scalar>
struct InputTable {
    using Vector = Eigen::Matrix<Scalar, kJoints, 1>;
    std::vector<Vector> position, torque;
    InputTable() : position(kInputTicks), torque(kInputTicks) {
        for (std::size_t t = 0; t < kInputTicks; ++t) {
            const double time = 1e-3 * static_cast<double>(t);
            for (int j = 0; j < kJoints; ++j) {
                const double f = 0.5 + 0.3 * j;
                position[t][j] = static_cast<Scalar>(std::sin(2 * M_PI * f * time) + 0.1 * std::sin(2 * M_PI * 9.0 * time + j));
                torque[t][j] = static_cast<Scalar>(std::cos(2 * M_PI * f * time));
            }
        }
    }
};

template <typename Scalar>
using Bank = jacobid::DifferentiatorBank<Scalar, kJoints, kCapacity>;
template <typename Scalar>
using Naive = NaiveBank<Scalar, kJoints, kCapacity>;

template <typename Scalar>
bool configure(Bank<Scalar>& bank) {
    return bank.configure(bank_config()).status == jacobid::BankStatus::Ok;
}

template <typename Scalar>
bool configure(Naive<Scalar>& naive) {
    Bank<Scalar> bank;
    if (!configure(bank)) return false;
    naive.configure(bank);
    return true;
}

template <typename Scalar>
void tick(Bank<Scalar>& bank, const InputTable<Scalar>& in, std::size_t t, jacobid::BankOutput<Scalar, kJoints>& out) {
    bank.step(in.position[t], in.torque[t], out);
}

template <typename Scalar>
void tick(Naive<Scalar>& naive, const InputTable<Scalar>& in, std::size_t t, jacobid::BankOutput<Scalar, kJoints>& out) {
    naive.step(in.position[t], in.torque[t], out);
}

template <typename Impl, typename Scalar>
void BM_Tick(benchmark::State& state) {
    static const InputTable<Scalar> in;
    static Impl impl;  // ~40 KiB: static, not on the benchmark thread's stack
    if (!configure(impl)) {
        state.SkipWithError("configure failed");
        return;
    }
    jacobid::BankOutput<Scalar, kJoints> out;
    std::size_t t = 0;
    for (std::size_t i = 0; i < kCapacity; ++i) tick(impl, in, i, out);  // full windows
    for (auto _ : state) {
        tick(impl, in, t, out);
        benchmark::DoNotOptimize(out);
        benchmark::ClobberMemory();
        t = (t + 1 == kInputTicks) ? 0 : t + 1;
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

// Median of the repetitions, reported in ns per tick.
void register_benchmarks() {
    auto tune = [](benchmark::internal::Benchmark* b) {
        b->Repetitions(10)->ReportAggregatesOnly(true)->MinTime(0.1)->Unit(benchmark::kNanosecond);
    };
    tune(benchmark::RegisterBenchmark("tick/bank_double", BM_Tick<Bank<double>, double>));
    tune(benchmark::RegisterBenchmark("tick/naive_double", BM_Tick<Naive<double>, double>));
    tune(benchmark::RegisterBenchmark("tick/bank_float", BM_Tick<Bank<float>, float>));
    tune(benchmark::RegisterBenchmark("tick/naive_float", BM_Tick<Naive<float>, float>));
}

// Console output plus a summary: median ns per tick, the 0.5 us target and the speed-up over the baseline.
class SummaryReporter : public benchmark::ConsoleReporter {
public:
    SummaryReporter() : ConsoleReporter(OO_Tabular) {}  // no colour codes: the output goes into logs and docs
    void ReportRuns(const std::vector<Run>& reports) override {
        ConsoleReporter::ReportRuns(reports);
        for (const Run& r : reports) {
            if (r.run_type == Run::RT_Aggregate && r.aggregate_name == "median") {
                median_[r.run_name.function_name] = {r.GetAdjustedRealTime(), r.GetAdjustedCPUTime()};
            }
        }
    }
    void Finalize() override {
        ConsoleReporter::Finalize();
        // Real time is what the target is about; CPU time is shown because a loaded machine (other jobs on
        // the 2 cores) inflates real time but not CPU time: if they differ much, rerun on a quiet machine.
        std::printf("\nsummary (median of repetitions, ns per tick, real / cpu)\n%-8s %20s %20s %10s %10s\n", "scalar",
                    "bank", "naive", "speed-up", "<= 500 ns");
        for (const char* scalar : {"double", "float"}) {
            const auto b = median_.find(std::string("tick/bank_") + scalar);
            const auto n = median_.find(std::string("tick/naive_") + scalar);
            if (b == median_.end() || n == median_.end()) continue;
            const Times& bank = b->second;
            const Times& naive = n->second;
            std::printf("%-8s %9.1f / %8.1f %9.1f / %8.1f %9.1fx %10s\n", scalar, bank.real, bank.cpu, naive.real, naive.cpu,
                        naive.real / bank.real, bank.real <= 500.0 ? "yes" : "NO");
        }
    }

private:
    struct Times {
        double real = 0, cpu = 0;
    };
    std::map<std::string, Times> median_;
};

// --driver: run `ticks` ticks of one implementation; the instruction count per tick is the difference
// between two tick counts divided by their difference (run_callgrind.sh), so configure() cancels out.
template <typename Impl, typename Scalar>
int drive(std::size_t ticks) {
    static const InputTable<Scalar> in;
    static Impl impl;
    if (!configure(impl)) return 2;
    jacobid::BankOutput<Scalar, kJoints> out;
    double checksum = 0;
    for (std::size_t t = 0; t < ticks; ++t) {
        tick(impl, in, t % kInputTicks, out);
        checksum += static_cast<double>(out.velocity[0]);
    }
    std::printf("%zu ticks, checksum %.6e\n", ticks, checksum);
    return 0;
}

// --driver=check: the baseline computes what the bank computes (same 18 dot products + torque delay).
template <typename Scalar>
int check(std::size_t ticks, double tolerance) {
    static const InputTable<Scalar> in;
    static Bank<Scalar> bank;
    static Naive<Scalar> naive;
    if (!configure(bank) || !configure(naive)) return 2;
    jacobid::BankOutput<Scalar, kJoints> a, b;
    for (std::size_t t = 0; t < ticks; ++t) {
        tick(bank, in, t % kInputTicks, a);
        tick(naive, in, t % kInputTicks, b);
        if (!a.valid) continue;
        const double err = std::max({(a.position - b.position).cwiseAbs().maxCoeff() / 1.0, (a.velocity - b.velocity).cwiseAbs().maxCoeff() / 10.0,
                                     (a.acceleration - b.acceleration).cwiseAbs().maxCoeff() / 1000.0,
                                     (a.torque - b.torque).cwiseAbs().maxCoeff() / 1.0});
        if (!(err <= tolerance)) {
            std::printf("mismatch at tick %zu: %g\n", t, err);
            return 1;
        }
    }
    std::printf("bank and baseline agree over %zu ticks\n", ticks);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    std::string driver;
    std::size_t ticks = 10000;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.rfind("--driver=", 0) == 0) driver = arg.substr(9);
        if (arg.rfind("--ticks=", 0) == 0) ticks = std::strtoull(arg.c_str() + 8, nullptr, 10);
    }
    if (!driver.empty()) {
        if (driver == "bank_double") return drive<Bank<double>, double>(ticks);
        if (driver == "bank_float") return drive<Bank<float>, float>(ticks);
        if (driver == "naive_double") return drive<Naive<double>, double>(ticks);
        if (driver == "naive_float") return drive<Naive<float>, float>(ticks);
        if (driver == "check") {
            const int d = check<double>(ticks, 1e-9);
            return d != 0 ? d : check<float>(ticks, 1e-3);
        }
        std::fprintf(stderr, "unknown --driver=%s\n", driver.c_str());
        return 2;
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    register_benchmarks();
    SummaryReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    return 0;
}
