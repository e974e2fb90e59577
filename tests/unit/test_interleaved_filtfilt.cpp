// SPDX-License-Identifier: MIT
// The pipeline's F_p filters many regressor columns at once (signal::InterleavedFiltfilt). Each column must
// come out as the one-signal jacobid::sosfiltfilt (itself checked against scipy in test_filtfilt) gives it,
// whatever the number of signals in the block and the lane a signal lands in.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/errors.hpp"
#include "jacobid/baseline/filtfilt.hpp"
#include "signal/baseline_response.hpp"
#include "signal/interleaved_filtfilt.hpp"

namespace {

using jacobid::Span;
using jacobid::signal::ButterworthSos;
using jacobid::signal::InterleavedFiltfilt;
using jacobid::signal::kFiltfiltLanes;

std::vector<double> one_signal(const ButterworthSos& sos, const std::vector<double>& x) {
    std::vector<double> y(x.size()), workspace(jacobid::sosfiltfilt_workspace_size(sos));
    EXPECT_EQ(jacobid::sosfiltfilt(sos, Span<const double>(x), Span<double>(y), Span<double>(workspace)), jacobid::FilterStatus::Ok);
    return y;
}

// Each output within 2 ulp of the magnitude that flows through the filter: the same operations, up to the
// compiler contracting a product and a sum into one fused multiply-add differently in the vectorized loop.
void expect_same(const std::vector<double>& expected, const std::vector<double>& actual, double scale, const char* what) {
    ASSERT_EQ(expected.size(), actual.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        ASSERT_NEAR(actual[i], expected[i], 4e-16 * scale) << what << " sample " << i;
    }
}

TEST(InterleavedFiltfilt, EverySignalEqualsTheOneSignalFilterForEveryBlockSizeAndOrder) {
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, 1.0);
    for (int order : {1, 2, 4, 5, 8, 16}) {
        const ButterworthSos sos = jacobid::signal::design_butterworth_or_throw(order, 9.0, 1e-3, "test");
        InterleavedFiltfilt filter(sos);
        ASSERT_EQ(filter.padlen(), jacobid::sosfiltfilt_padlen(sos));
        for (std::size_t count : {std::size_t{1}, std::size_t{3}, kFiltfiltLanes - 1, kFiltfiltLanes}) {
            for (std::size_t n : {filter.padlen() + 1, filter.padlen() + 2, std::size_t{5000}}) {
                std::vector<std::vector<double>> x(count, std::vector<double>(n));
                for (std::size_t l = 0; l < count; ++l) {
                    // Offsets, slopes and noise differ per lane: the edges' reflections and steady states differ.
                    for (std::size_t i = 0; i < n; ++i) x[l][i] = 10.0 * static_cast<double>(l) - 3.0 + 1e-3 * static_cast<double>(i * l) + noise(rng);
                }
                std::vector<std::vector<double>> y = x;
                std::vector<double*> pointers;
                for (auto& v : y) pointers.push_back(v.data());
                filter.filter_in_place(pointers.data(), count, n);
                for (std::size_t l = 0; l < count; ++l) {
                    double scale = 0.0;
                    for (double v : x[l]) scale = std::max(scale, std::abs(v));
                    expect_same(one_signal(sos, x[l]), y[l], 100.0 * scale, "lane");
                }
            }
        }
    }
}

TEST(InterleavedFiltfilt, ALaneDoesNotSeeItsNeighbours) {
    // A signal's output is the same alone and beside signals a million times larger.
    const ButterworthSos sos = jacobid::signal::design_butterworth_or_throw(4, 5.0, 1e-3, "test");
    InterleavedFiltfilt filter(sos);
    const std::size_t n = 3000;
    std::vector<double> small(n), big(n);
    for (std::size_t i = 0; i < n; ++i) {
        small[i] = std::sin(0.01 * static_cast<double>(i));
        big[i] = 1e6 * std::cos(0.03 * static_cast<double>(i));
    }
    std::vector<double> alone = small, beside = small, other = big;
    double* one[] = {alone.data()};
    filter.filter_in_place(one, 1, n);
    double* two[] = {other.data(), beside.data()};
    filter.filter_in_place(two, 2, n);
    EXPECT_EQ(alone, beside);
    // And a known property, independent of any implementation: a zero-phase low-pass passes a constant unchanged.
    std::vector<double> constant(n, 2.5);
    double* c[] = {constant.data()};
    filter.filter_in_place(c, 1, n);
    for (double v : constant) ASSERT_NEAR(v, 2.5, 1e-10);  // the cascade's DC gain is 1 to rounding
}

TEST(InterleavedFiltfilt, RefusesASignalNoLongerThanTheEdgeExtension) {
    const ButterworthSos sos = jacobid::signal::design_butterworth_or_throw(4, 5.0, 1e-3, "test");
    InterleavedFiltfilt filter(sos);
    std::vector<double> x(filter.padlen(), 1.0);
    double* one[] = {x.data()};
    EXPECT_THROW(filter.filter_in_place(one, 1, x.size()), jacobid::InputError);
    EXPECT_THROW(filter.filter_in_place(one, 0, x.size() + 10), jacobid::InputError);
}

}  // namespace
