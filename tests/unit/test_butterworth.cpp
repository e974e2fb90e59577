// SPDX-License-Identifier: MIT
// Butterworth and Chebyshev I low-pass design: coefficients against scipy.signal.butter / cheby1
// (output='sos'), frequency-response properties that follow from the definitions, and the error paths.
#include "jacobid/baseline/butterworth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

#include "../reference/scipy_reference.hpp"

namespace {

using jacobid::FilterStatus;
using jacobid::SosCascade;
using namespace jacobid::reference;  // the scipy runs and comparisons of the baseline tests

constexpr std::size_t kCapacity = 4;  // orders 1..8
constexpr double kCoefficientTolerance = 1e-9;
constexpr double kPi = 3.141592653589793;
const std::string kOrdersOneToEight = "1,2,3,4,5,6,7,8";

// H(e^{j omega}) of the cascade, omega in rad/sample.
std::complex<double> frequency_response(const SosCascade<kCapacity>& sos, double omega) {
    const std::complex<double> z1 = std::polar(1.0, -omega);  // z^-1
    std::complex<double> response(1.0, 0.0);
    for (std::size_t i = 0; i < sos.count; ++i) {
        const auto& s = sos.sections[i];
        response *= (s[0] + s[1] * z1 + s[2] * z1 * z1) / (s[3] + s[4] * z1 + s[5] * z1 * z1);
    }
    return response;
}

struct ButterworthCase {
    double cutoff_hz;
    double sample_rate_hz;
};

class ButterworthMatchesScipy : public ::testing::TestWithParam<ButterworthCase> {};

TEST_P(ButterworthMatchesScipy, OrdersOneToEight) {
    const ButterworthCase c = GetParam();
    const auto reference =
        run_scipy_baseline("butter " + kOrdersOneToEight + " " + exact(c.cutoff_hz) + " " + exact(c.sample_rate_hz));
    for (int order = 1; order <= 8; ++order) {
        SCOPED_TRACE("order " + std::to_string(order));
        SosCascade<kCapacity> sos;
        ASSERT_EQ(jacobid::butterworth_lowpass(order, c.cutoff_hz, c.sample_rate_hz, sos), FilterStatus::Ok);
        EXPECT_EQ(sos.count, static_cast<std::size_t>(order + 1) / 2);
        EXPECT_LE(sos_relative_error(sos, array_named(reference, "sos_" + std::to_string(order))),
                  kCoefficientTolerance);
    }
}

INSTANTIATE_TEST_SUITE_P(
    Cutoffs, ButterworthMatchesScipy,
    ::testing::Values(ButterworthCase{5.0, 1000.0},   // very low normalized cutoff (unusable as (b, a))
                      ButterworthCase{1.0, 1000.0},   // lower still
                      ButterworthCase{25.0, 1000.0},  // paper section III: order 6 at 25 Hz, 1 kHz
                      ButterworthCase{0.1, 2.0},      // paper: 0.1 * (fs / 2), normalized
                      ButterworthCase{200.0, 1000.0},
                      ButterworthCase{250.0, 1000.0},  // Wn = 0.5: poles on the imaginary axis and near 0
                      ButterworthCase{450.0, 1000.0}   // near Nyquist: poles in the left half plane
                      ));

class DecimateLowpassChebyshevMatchesScipy : public ::testing::TestWithParam<double> {};

// Chebyshev I is here for decimation (scipy.signal.decimate uses cheby1(8, 0.05, 0.8 / q)), hence the
// suite names; other orders and ripples exercise the odd-order pairing and the even-order gain.
TEST_P(DecimateLowpassChebyshevMatchesScipy, OrdersOneToEight) {
    const double normalized_cutoff = GetParam();
    for (double ripple_db : {0.05, 1.0, 3.0}) {
        const auto reference =
            run_scipy_baseline("cheby1 " + kOrdersOneToEight + " " + exact(ripple_db) + " " + exact(normalized_cutoff));
        for (int order = 1; order <= 8; ++order) {
            SCOPED_TRACE("order " + std::to_string(order) + ", ripple " + std::to_string(ripple_db) + " dB");
            SosCascade<kCapacity> sos;
            ASSERT_EQ(jacobid::chebyshev1_lowpass(order, ripple_db, normalized_cutoff, 2.0, sos), FilterStatus::Ok);
            EXPECT_LE(sos_relative_error(sos, array_named(reference, "sos_" + std::to_string(order))),
                      kCoefficientTolerance);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(DecimationEdges, DecimateLowpassChebyshevMatchesScipy,
                         ::testing::Values(0.8 / 2.0, 0.8 / 3.0, 0.8 / 5.0, 0.8 / 10.0, 0.8 / 50.0));

// Definition of the Butterworth low-pass: |H| = 1 at DC, 1/sqrt(2) at the cutoff (the bilinear transform
// is prewarped to put it exactly there), 0 at Nyquist (all zeros at z = -1), and monotonic.
TEST(ButterworthResponse, UnityAtDcHalfPowerAtCutoffZeroAtNyquist) {
    for (int order = 1; order <= 8; ++order) {
        for (double cutoff_hz : {5.0, 25.0, 100.0, 400.0}) {
            SCOPED_TRACE("order " + std::to_string(order) + ", cutoff " + std::to_string(cutoff_hz));
            SosCascade<kCapacity> sos;
            ASSERT_EQ(jacobid::butterworth_lowpass(order, cutoff_hz, 1000.0, sos), FilterStatus::Ok);
            EXPECT_NEAR(std::abs(frequency_response(sos, 0.0)), 1.0, 1e-9);
            EXPECT_NEAR(sos.dc_gain(), 1.0, 1e-9);
            EXPECT_NEAR(std::abs(frequency_response(sos, 2.0 * kPi * cutoff_hz / 1000.0)), std::sqrt(0.5), 1e-9);
            EXPECT_NEAR(std::abs(frequency_response(sos, kPi)), 0.0, 1e-12);
            double previous = 2.0;
            for (int k = 0; k <= 100; ++k) {
                const double magnitude = std::abs(frequency_response(sos, kPi * k / 100.0));
                EXPECT_LE(magnitude, previous + 1e-12);
                previous = magnitude;
            }
        }
    }
}

// Definition of the Chebyshev I low-pass: the pass band ripples between 1 and 10^(-rp/20); the gain is
// 10^(-rp/20) at the edge, 1 at DC for odd orders and 10^(-rp/20) at DC for even orders.
TEST(DecimateLowpassChebyshevResponse, RippleBandAndEdge) {
    const double ripple_db = 1.0;
    const double bottom = std::pow(10.0, -ripple_db / 20.0);
    for (int order = 1; order <= 8; ++order) {
        SCOPED_TRACE("order " + std::to_string(order));
        SosCascade<kCapacity> sos;
        ASSERT_EQ(jacobid::chebyshev1_lowpass(order, ripple_db, 0.3, 2.0, sos), FilterStatus::Ok);
        EXPECT_NEAR(sos.dc_gain(), order % 2 == 1 ? 1.0 : bottom, 1e-9);
        EXPECT_NEAR(std::abs(frequency_response(sos, 0.3 * kPi)), bottom, 1e-9);
        for (int k = 0; k <= 100; ++k) {
            const double magnitude = std::abs(frequency_response(sos, 0.3 * kPi * k / 100.0));
            EXPECT_LE(magnitude, 1.0 + 1e-9);
            EXPECT_GE(magnitude, bottom - 1e-9);
        }
    }
}

// A cascade filled before a failed design must come out unchanged.
SosCascade<kCapacity> marked_cascade() {
    SosCascade<kCapacity> sos;
    sos.count = 1;
    sos.sections[0] = {7.0, 7.0, 7.0, 1.0, 7.0, 7.0};
    return sos;
}

void expect_unchanged(const SosCascade<kCapacity>& sos) {
    const SosCascade<kCapacity> marked = marked_cascade();
    EXPECT_EQ(sos.count, marked.count);
    EXPECT_EQ(sos.sections, marked.sections);
}

TEST(ButterworthDesignErrors, OrderBelowOneIsInvalidOrder) {
    for (int order : {0, -1, -8}) {
        SosCascade<kCapacity> sos = marked_cascade();
        EXPECT_EQ(jacobid::butterworth_lowpass(order, 25.0, 1000.0, sos), FilterStatus::InvalidOrder);
        EXPECT_EQ(jacobid::chebyshev1_lowpass(order, 0.05, 25.0, 1000.0, sos), FilterStatus::InvalidOrder);
        expect_unchanged(sos);
    }
}

TEST(ButterworthDesignErrors, MoreSectionsThanCapacityIsCapacityExceeded) {
    SosCascade<kCapacity> four = marked_cascade();
    EXPECT_EQ(jacobid::butterworth_lowpass(9, 25.0, 1000.0, four), FilterStatus::CapacityExceeded);
    EXPECT_EQ(jacobid::chebyshev1_lowpass(9, 0.05, 25.0, 1000.0, four), FilterStatus::CapacityExceeded);
    expect_unchanged(four);
    SosCascade<1> one;
    EXPECT_EQ(jacobid::butterworth_lowpass(3, 25.0, 1000.0, one), FilterStatus::CapacityExceeded);
    EXPECT_EQ(jacobid::butterworth_lowpass(2, 25.0, 1000.0, one), FilterStatus::Ok);
}

TEST(ButterworthDesignErrors, NonPositiveOrNonFiniteSampleRateIsInvalidSampling) {
    for (double fs :
         {0.0, -1000.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        SosCascade<kCapacity> sos = marked_cascade();
        EXPECT_EQ(jacobid::butterworth_lowpass(4, 25.0, fs, sos), FilterStatus::InvalidSampling);
        EXPECT_EQ(jacobid::chebyshev1_lowpass(4, 0.05, 25.0, fs, sos), FilterStatus::InvalidSampling);
        expect_unchanged(sos);
    }
}

TEST(ButterworthDesignErrors, CutoffOutsideZeroToNyquistIsInvalidCutoff) {
    for (double cutoff :
         {0.0, -5.0, 500.0, 800.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        SosCascade<kCapacity> sos = marked_cascade();
        EXPECT_EQ(jacobid::butterworth_lowpass(4, cutoff, 1000.0, sos), FilterStatus::InvalidCutoff);
        EXPECT_EQ(jacobid::chebyshev1_lowpass(4, 0.05, cutoff, 1000.0, sos), FilterStatus::InvalidCutoff);
        expect_unchanged(sos);
    }
    SosCascade<kCapacity> sos;
    EXPECT_EQ(jacobid::butterworth_lowpass(4, 499.9, 1000.0, sos), FilterStatus::Ok);
}

TEST(ButterworthDesignErrors, NonPositiveOrNonFiniteRippleIsInvalidRipple) {
    for (double ripple :
         {0.0, -0.5, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        SosCascade<kCapacity> sos = marked_cascade();
        EXPECT_EQ(jacobid::chebyshev1_lowpass(4, ripple, 25.0, 1000.0, sos), FilterStatus::InvalidRipple);
        expect_unchanged(sos);
    }
}

// The reference cache (tests/reference/scipy_reference.hpp) answers from its entry only when the entry repeats
// the script and the arguments: an entry whose values were changed is read back as such (so it is read, not
// recomputed), and one whose key no longer matches is recomputed by scipy.
TEST(ScipyReferenceCache, AnEntryIsReadOnlyWhenItsKeyMatches) {
    namespace fs = std::filesystem;
    const fs::path cache = fs::temp_directory_path() / ("jacobid-reference-cache-" + std::to_string(::getpid()));
    fs::remove_all(cache);
    const char* previous = std::getenv("JACOBID_REFERENCE_CACHE");
    const std::string kept_previous = previous ? previous : "";
    ::setenv("JACOBID_REFERENCE_CACHE", cache.c_str(), 1);
    const std::string arguments = "butter 2 25 1000";
    const auto computed = run_scipy_baseline(arguments);
    ASSERT_EQ(array_named(computed, "sos_2").size(), 6u);
    ASSERT_EQ(std::distance(fs::directory_iterator(cache), fs::directory_iterator()), 1);
    const fs::path entry = fs::directory_iterator(cache)->path();
    std::string text = jacobid::test::file_text(entry);
    const std::size_t line = text.rfind("sos_2 ");
    ASSERT_NE(line, std::string::npos);

    std::ofstream(entry, std::ios::binary) << text.substr(0, line) << "sos_2 1 2 3 4 5 6\n";
    EXPECT_EQ(array_named(run_scipy_baseline(arguments), "sos_2"), (std::vector<double>{1, 2, 3, 4, 5, 6}));

    std::ofstream(entry, std::ios::binary) << "another script\n" << text.substr(text.find("\n--arguments")) << "sos_2 1 2 3 4 5 6\n";
    EXPECT_EQ(array_named(run_scipy_baseline(arguments), "sos_2"), array_named(computed, "sos_2"));

    if (previous) ::setenv("JACOBID_REFERENCE_CACHE", kept_previous.c_str(), 1); else ::unsetenv("JACOBID_REFERENCE_CACHE");
    fs::remove_all(cache);
}

}  // namespace
