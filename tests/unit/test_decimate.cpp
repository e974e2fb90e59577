// SPDX-License-Identifier: MIT
// Decimation against scipy.signal.decimate (default Chebyshev I low-pass, and a Butterworth low-pass given
// to scipy as a dlti system), sizes, and the error paths.
#include "jacobid/baseline/decimate.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../reference/scipy_reference.hpp"

namespace {

using jacobid::FilterStatus;
using jacobid::SosCascade;
using jacobid::Span;
using namespace jacobid::reference;  // the scipy runs and comparisons of the baseline tests

constexpr double kSignalTolerance = 1e-9;  // relative to the largest |x|

struct DecimateCase {
    std::size_t factor;
    std::size_t length;
};

class DefaultDecimateMatchesScipy : public ::testing::TestWithParam<DecimateCase> {};

TEST_P(DefaultDecimateMatchesScipy, LowpassAndSamples) {
    const DecimateCase c = GetParam();
    const auto reference =
        run_scipy_baseline("decimate " + std::to_string(c.factor) + " " + std::to_string(c.length) + " 5");
    const std::vector<double>& x = array_named(reference, "x");
    const std::vector<double>& expected = array_named(reference, "y");

    jacobid::DecimationLowpass lowpass;
    ASSERT_EQ(jacobid::decimation_lowpass(c.factor, lowpass), FilterStatus::Ok);
    EXPECT_LE(sos_relative_error(lowpass, array_named(reference, "sos")), 1e-9);

    EXPECT_EQ(jacobid::decimated_size(x.size(), c.factor), expected.size());
    std::vector<double> y(jacobid::decimated_size(x.size(), c.factor));
    std::vector<double> workspace(jacobid::default_decimate_workspace_size(x.size()));
    ASSERT_EQ(jacobid::decimate(c.factor, Span<const double>(x.data(), x.size()), y, workspace), FilterStatus::Ok);
    EXPECT_LE(max_abs_difference(y, expected), kSignalTolerance * max_abs(x));
}

INSTANTIATE_TEST_SUITE_P(Factors, DefaultDecimateMatchesScipy,
                         ::testing::Values(DecimateCase{1, 300}, DecimateCase{2, 1000}, DecimateCase{3, 1001},
                                           DecimateCase{4, 1003}, DecimateCase{5, 2000}, DecimateCase{10, 2999},
                                           DecimateCase{2, 28}));  // shortest signal accepted: padlen 27 + 1

struct ButterworthDecimateCase {
    std::size_t factor;
    int order;
    double cutoff_hz;
    std::size_t length;
};

class ButterworthDecimateMatchesScipy : public ::testing::TestWithParam<ButterworthDecimateCase> {};

TEST_P(ButterworthDecimateMatchesScipy, Samples) {
    const ButterworthDecimateCase c = GetParam();
    const auto reference =
        run_scipy_baseline("decimate_butter " + std::to_string(c.factor) + " " + std::to_string(c.order) + " " +
                           exact(c.cutoff_hz) + " 1000 " + std::to_string(c.length) + " 9");
    const std::vector<double>& x = array_named(reference, "x");
    SosCascade<4> lowpass;
    ASSERT_EQ(jacobid::butterworth_lowpass(c.order, c.cutoff_hz, 1000.0, lowpass), FilterStatus::Ok);

    std::vector<double> y(jacobid::decimated_size(x.size(), c.factor));
    std::vector<double> workspace(jacobid::decimate_workspace_size(x.size(), lowpass));
    ASSERT_EQ(jacobid::decimate(lowpass, c.factor, Span<const double>(x.data(), x.size()), y, workspace),
              FilterStatus::Ok);
    EXPECT_LE(max_abs_difference(y, array_named(reference, "y")), kSignalTolerance * max_abs(x));
}

INSTANTIATE_TEST_SUITE_P(Lowpasses, ButterworthDecimateMatchesScipy,
                         ::testing::Values(ButterworthDecimateCase{10, 6, 25.0, 3000},  // paper's filter
                                           ButterworthDecimateCase{4, 4, 50.0, 1001},
                                           ButterworthDecimateCase{20, 3, 5.0, 4001}));

TEST(Decimate, KeepsEveryFactorthSampleFromIndexZero) {
    // The identity cascade (no section) isolates the sample selection: y[i] = x[i * q].
    const SosCascade<1> identity;
    std::vector<double> x;
    for (int k = 0; k < 23; ++k) x.push_back(k);
    std::vector<double> y(jacobid::decimated_size(x.size(), 5));
    std::vector<double> workspace(jacobid::decimate_workspace_size(x.size(), identity));
    ASSERT_EQ(jacobid::decimate(identity, 5, Span<const double>(x.data(), x.size()), y, workspace), FilterStatus::Ok);
    EXPECT_EQ(y, (std::vector<double>{0.0, 5.0, 10.0, 15.0, 20.0}));
}

// Error paths: each status comes from the condition it names, and y is not written.
class DecimateErrors : public ::testing::Test {
protected:
    static constexpr std::size_t kLength = 100;
    static constexpr std::size_t kFactor = 4;
    static constexpr double kUntouched = 12345.0;

    void SetUp() override {
        ASSERT_EQ(jacobid::decimation_lowpass(kFactor, lowpass), FilterStatus::Ok);
        x.assign(kLength, 1.0);
        y.assign(jacobid::decimated_size(kLength, kFactor), kUntouched);
        workspace.assign(jacobid::default_decimate_workspace_size(kLength), 0.0);
    }
    FilterStatus run_default(std::size_t factor, std::size_t x_size, std::size_t y_size, std::size_t workspace_size) {
        return jacobid::decimate(factor, Span<const double>(x.data(), x_size), Span<double>(y.data(), y_size),
                                 Span<double>(workspace.data(), workspace_size));
    }
    FilterStatus run_cascade(const jacobid::DecimationLowpass& cascade, std::size_t factor, std::size_t x_size,
                             std::size_t y_size, std::size_t workspace_size) {
        return jacobid::decimate(cascade, factor, Span<const double>(x.data(), x_size), Span<double>(y.data(), y_size),
                                 Span<double>(workspace.data(), workspace_size));
    }
    void expect_y_untouched() const {
        for (double v : y) EXPECT_EQ(v, kUntouched);
    }
    jacobid::DecimationLowpass lowpass;
    std::vector<double> x, y, workspace;
};

TEST_F(DecimateErrors, FactorZeroIsInvalidFactor) {
    EXPECT_EQ(run_default(0, kLength, y.size(), workspace.size()), FilterStatus::InvalidFactor);
    EXPECT_EQ(run_cascade(lowpass, 0, kLength, y.size(), workspace.size()), FilterStatus::InvalidFactor);
    jacobid::DecimationLowpass designed;
    EXPECT_EQ(jacobid::decimation_lowpass(0, designed), FilterStatus::InvalidFactor);
    expect_y_untouched();
}

TEST_F(DecimateErrors, MalformedCascadeIsInvalidCascade) {
    jacobid::DecimationLowpass unnormalized = lowpass;
    unnormalized.sections[0][3] = 0.5;
    EXPECT_EQ(run_cascade(unnormalized, kFactor, kLength, y.size(), workspace.size()), FilterStatus::InvalidCascade);
    jacobid::DecimationLowpass too_many = lowpass;
    too_many.count = 5;
    EXPECT_EQ(run_cascade(too_many, kFactor, kLength, y.size(), workspace.size()), FilterStatus::InvalidCascade);
    expect_y_untouched();
}

TEST_F(DecimateErrors, OutputNotCeilOfLengthOverFactorIsOutputSizeMismatch) {
    EXPECT_EQ(jacobid::decimated_size(kLength, kFactor), 25u);
    EXPECT_EQ(run_default(kFactor, kLength, 24, workspace.size()), FilterStatus::OutputSizeMismatch);
    EXPECT_EQ(run_default(kFactor, kLength - 1, 24, workspace.size()), FilterStatus::OutputSizeMismatch);
    EXPECT_EQ(run_default(kFactor, kLength - 1, 25, workspace.size()), FilterStatus::Ok);  // ceil(99 / 4) = 25
}

TEST_F(DecimateErrors, SignalNotLongerThanPadlenIsSignalTooShort) {
    const std::size_t padlen = jacobid::sosfiltfilt_padlen(lowpass);
    EXPECT_EQ(padlen, 27u);  // 3 * (2 * 4 + 1): scipy's "padlen, which is 27" for its decimate
    const std::size_t out = jacobid::decimated_size(padlen, kFactor);
    EXPECT_EQ(run_default(kFactor, padlen, out, workspace.size()), FilterStatus::SignalTooShort);
    expect_y_untouched();
}

TEST_F(DecimateErrors, WorkspaceBelowDocumentedSizeIsWorkspaceTooSmall) {
    EXPECT_EQ(jacobid::decimate_workspace_size(kLength, lowpass), workspace.size());
    EXPECT_EQ(run_default(kFactor, kLength, y.size(), workspace.size() - 1), FilterStatus::WorkspaceTooSmall);
    EXPECT_EQ(run_cascade(lowpass, kFactor, kLength, y.size(), kLength), FilterStatus::WorkspaceTooSmall);
    expect_y_untouched();
    EXPECT_EQ(run_default(kFactor, kLength, y.size(), workspace.size()), FilterStatus::Ok);
}

}  // namespace
