// SPDX-License-Identifier: MIT
// FFT (overlap-save) batch path: same outputs as the direct path to 1e-12 relative to sum|w||x|, same
// output size and error statuses, for block sizes that do and do not divide the record.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "jacobid/batch_differentiate.hpp"
#include "signal/fft_convolver.hpp"

namespace {

using jacobid::BatchStatus;
using jacobid::Span;
using jacobid::signal::FftConvolver;
using jacobid::signal::FftPlanning;

std::vector<double> random_vector(std::size_t n, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<double> v(n);
    for (auto& e : v) e = u(rng);
    return v;
}

// |a[j] - b[j]| <= 1e-12 * sum_k |w[k]| |x[j+k]| for every output.
void expect_matches_direct(const std::vector<double>& w, const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t taps = w.size();
    std::vector<double> ref(jacobid::batch_output_size(x.size(), taps));
    ASSERT_EQ(jacobid::differentiate_direct(Span<const double>(w), Span<const double>(x), Span<double>(ref)), BatchStatus::Ok);
    ASSERT_GE(y.size(), ref.size());
    for (std::size_t j = 0; j < ref.size(); ++j) {
        double magnitude = 0;
        for (std::size_t k = 0; k < taps; ++k) magnitude += std::abs(w[k] * x[j + k]);
        ASSERT_LE(std::abs(y[j] - ref[j]), 1e-12 * magnitude) << "taps " << taps << " n " << x.size() << " j " << j;
    }
}

TEST(FftConvolver, MatchesDirectPathForManyKernelAndSignalLengths) {
    std::mt19937 rng(11);
    for (std::size_t taps : {1u, 2u, 3u, 16u, 63u, 64u, 65u, 211u, 601u, 1101u}) {
        const std::vector<double> w = random_vector(taps, rng);
        const FftConvolver conv{Span<const double>(w)};
        ASSERT_EQ(conv.taps(), taps);
        ASSERT_EQ(conv.fft_size(), FftConvolver::default_fft_size(taps));
        const std::size_t step = conv.block_outputs();
        ASSERT_EQ(step, conv.fft_size() - taps + 1);
        // Signal length == taps (one output), one sample short of / exactly / one past a whole number of
        // blocks, and lengths that are not a multiple of the block.
        for (std::size_t n : {taps, taps + 1, taps + 7, taps - 1 + step, taps + step, taps + 1 + step, taps - 1 + 3 * step,
                              taps + 3 * step + 101, 5 * conv.fft_size() + 13}) {
            const std::vector<double> x = random_vector(n, rng);
            std::vector<double> y(jacobid::batch_output_size(n, taps), 0.0);
            ASSERT_EQ(conv.correlate(Span<const double>(x), Span<double>(y)), BatchStatus::Ok);
            expect_matches_direct(w, x, y);
        }
    }
}

TEST(FftConvolver, ExplicitBlockSizesAndMeasuredPlansAgree) {
    std::mt19937 rng(12);
    const std::vector<double> w = random_vector(211, rng);
    const std::vector<double> x = random_vector(10'000, rng);
    // 211 (smallest legal block: one output per block), non powers of two, and a block longer than x.
    for (std::size_t fft_size : {211u, 256u, 300u, 1000u, 2048u, 16384u}) {
        for (FftPlanning planning : {FftPlanning::Estimate, FftPlanning::Measure}) {
            // Measuring plans takes up to a second per size: once is enough to show it changes nothing.
            if (planning == FftPlanning::Measure && fft_size != 2048u) continue;
            const FftConvolver conv(Span<const double>(w), fft_size, planning);
            ASSERT_EQ(conv.fft_size(), fft_size);
            std::vector<double> y(jacobid::batch_output_size(x.size(), w.size()));
            ASSERT_EQ(conv.correlate(Span<const double>(x), Span<double>(y)), BatchStatus::Ok);
            expect_matches_direct(w, x, y);
        }
    }
    // A block smaller than the kernel is raised to the default.
    EXPECT_EQ(FftConvolver(Span<const double>(w), 100).fft_size(), FftConvolver::default_fft_size(211));
}

TEST(FftConvolver, DoesNotWritePastTheOutputs) {
    std::mt19937 rng(13);
    const std::vector<double> w = random_vector(101, rng);
    const std::vector<double> x = random_vector(3'000, rng);
    const std::size_t outputs = jacobid::batch_output_size(x.size(), w.size());
    std::vector<double> y(outputs + 50, 42.0);
    ASSERT_EQ(FftConvolver(Span<const double>(w)).correlate(Span<const double>(x), Span<double>(y)), BatchStatus::Ok);
    for (std::size_t j = outputs; j < y.size(); ++j) EXPECT_EQ(y[j], 42.0);
}

TEST(FftConvolver, ReportsTheSameErrorsAsTheDirectPath) {
    std::vector<double> w(11, 1.0), x(10, 1.0), y(1);
    const FftConvolver conv{Span<const double>(w)};
    EXPECT_EQ(conv.correlate(Span<const double>(x), Span<double>(y)), BatchStatus::SignalShorterThanWindow);
    x.resize(12);
    EXPECT_EQ(conv.correlate(Span<const double>(x), Span<double>(y)), BatchStatus::OutputTooSmall);
    const FftConvolver empty{Span<const double>()};
    EXPECT_EQ(empty.taps(), 0u);
    EXPECT_EQ(empty.correlate(Span<const double>(x), Span<double>(y)), BatchStatus::EmptyKernel);

    using jacobid::signal::differentiate_batch;
    // The same three errors through the dispatcher, for a short (direct) and a long (FFT) kernel.
    for (std::size_t taps : {std::size_t{11}, 2 * jacobid::signal::kFftCrossoverTaps}) {
        std::vector<double> wk(taps, 1.0), xs(taps - 1, 1.0), xl(taps + 1, 1.0), ys(1);
        EXPECT_EQ(differentiate_batch(Span<const double>(wk), Span<const double>(xs), Span<double>(ys)), BatchStatus::SignalShorterThanWindow);
        EXPECT_EQ(differentiate_batch(Span<const double>(wk), Span<const double>(xl), Span<double>(ys)), BatchStatus::OutputTooSmall);
    }
    EXPECT_EQ(differentiate_batch(Span<const double>(), Span<const double>(x), Span<double>(y)), BatchStatus::EmptyKernel);
}

TEST(FftConvolver, MovedConvolverKeepsWorking) {
    std::mt19937 rng(14);
    const std::vector<double> w = random_vector(65, rng);
    const std::vector<double> x = random_vector(2'000, rng);
    FftConvolver a{Span<const double>(w)};
    FftConvolver b = std::move(a);
    std::vector<double> y(jacobid::batch_output_size(x.size(), w.size()));
    ASSERT_EQ(b.correlate(Span<const double>(x), Span<double>(y)), BatchStatus::Ok);
    expect_matches_direct(w, x, y);
}

TEST(DifferentiateBatch, MatchesDirectPathOnBothSidesOfTheCrossover) {
    std::mt19937 rng(15);
    const std::size_t crossover = jacobid::signal::kFftCrossoverTaps;
    for (std::size_t taps : {std::size_t{5}, crossover - 1, crossover, std::size_t{211}, std::size_t{1101}}) {
        const std::vector<double> w = random_vector(taps, rng);
        // Small jobs (direct whatever the kernel) and jobs large enough for the FFT path.
        for (std::size_t n : {taps, taps + 500, taps + (jacobid::signal::kFftMinimumWork / taps) + 3000}) {
            const std::vector<double> x = random_vector(n, rng);
            std::vector<double> y(jacobid::batch_output_size(n, taps));
            ASSERT_EQ(jacobid::signal::differentiate_batch(Span<const double>(w), Span<const double>(x), Span<double>(y)), BatchStatus::Ok);
            expect_matches_direct(w, x, y);
        }
    }
}

}  // namespace
