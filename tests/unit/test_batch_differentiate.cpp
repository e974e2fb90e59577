// SPDX-License-Identifier: MIT
// Batch (direct) differentiation: equals the textbook correlation, drops the ends, rejects short input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "jacobid/batch_differentiate.hpp"
#include "jacobid/ring_window.hpp"

namespace {

TEST(BatchDifferentiate, EqualsNaiveCorrelation) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    for (std::size_t taps : {1u, 5u, 17u, 211u}) {
        for (std::size_t n : {taps, taps + 1, taps + 15, taps + 16, taps + 1000}) {
            std::vector<double> w(taps), x(n), y(jacobid::batch_output_size(n, taps));
            for (auto& v : w) v = u(rng);
            for (auto& v : x) v = u(rng);
            ASSERT_EQ(jacobid::differentiate_direct(jacobid::Span<const double>(w), jacobid::Span<const double>(x), jacobid::Span<double>(y)),
                      jacobid::BatchStatus::Ok);
            ASSERT_EQ(y.size(), n - taps + 1);
            for (std::size_t j = 0; j < y.size(); ++j) {
                double ref = 0;
                for (std::size_t k = 0; k < taps; ++k) ref += w[k] * x[j + k];
                ASSERT_NEAR(y[j], ref, 1e-12 * static_cast<double>(taps)) << taps << " " << n << " " << j;
            }
        }
    }
}

TEST(BatchDifferentiate, RejectsShortSignalsAndSmallOutputs) {
    std::vector<double> w(11, 1.0), x(10, 1.0), y(1);
    EXPECT_EQ(jacobid::differentiate_direct(jacobid::Span<const double>(w), jacobid::Span<const double>(x), jacobid::Span<double>(y)),
              jacobid::BatchStatus::SignalShorterThanWindow);
    x.resize(12);
    EXPECT_EQ(jacobid::differentiate_direct(jacobid::Span<const double>(w), jacobid::Span<const double>(x), jacobid::Span<double>(y)),
              jacobid::BatchStatus::OutputTooSmall);
    EXPECT_EQ(jacobid::differentiate_direct(jacobid::Span<const double>(), jacobid::Span<const double>(x), jacobid::Span<double>(y)),
              jacobid::BatchStatus::EmptyKernel);
    EXPECT_DOUBLE_EQ(jacobid::batch_offset_samples(211, 0.0), 105.0);
    EXPECT_DOUBLE_EQ(jacobid::batch_offset_samples(211, 1.0), 210.0);
}

TEST(RingWindow, WindowIsContiguousAndOrderedOldestFirst) {
    jacobid::RingWindow<int, 5> r;
    for (int i = 1; i <= 13; ++i) {
        r.push(i);
        const int* w = r.window(std::min(i, 5));
        for (int k = 0; k < std::min(i, 5); ++k) EXPECT_EQ(w[k], i - std::min(i, 5) + 1 + k);
        EXPECT_EQ(r.at_lag(0), i);
    }
    EXPECT_EQ(r.filled(), 5u);
    const int* lagged = r.window(3, 2);  // samples 9, 10, 11
    EXPECT_EQ(lagged[0], 9);
    EXPECT_EQ(lagged[2], 11);
}

}  // namespace
