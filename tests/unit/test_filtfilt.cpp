// SPDX-License-Identifier: MIT
// Streaming SOS filter, sosfilt_zi and zero-phase sosfiltfilt against scipy.signal, the padlen
// boundary against scipy's own acceptance, and the error paths.
#include "jacobid/baseline/filtfilt.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "../reference/scipy_reference.hpp"
#include "jacobid/baseline/butterworth.hpp"

namespace {

using jacobid::FilterStatus;
using jacobid::SosCascade;
using namespace jacobid::reference;  // the scipy runs and comparisons of the baseline tests

constexpr std::size_t kCapacity = 4;
constexpr double kSignalTolerance = 1e-9;  // relative to the largest |x|

struct FilterCase {
    int order;
    double cutoff_hz;
    double sample_rate_hz;
    std::size_t length;
};

std::string describe_case(const FilterCase& c) {
    return std::to_string(c.order) + " " + exact(c.cutoff_hz) + " " + exact(c.sample_rate_hz);
}

std::vector<double> sosfilt_from_rest(const SosCascade<kCapacity>& sos, const std::vector<double>& x) {
    jacobid::SosFilterState<kCapacity> filter(sos);
    std::vector<double> y;
    for (double sample : x) y.push_back(filter.step(sample));
    return y;
}

std::vector<double> flatten(const jacobid::SosState<kCapacity>& zi, std::size_t sections) {
    std::vector<double> flat;
    for (std::size_t i = 0; i < sections; ++i) flat.insert(flat.end(), zi[i].begin(), zi[i].end());
    return flat;
}

std::vector<double> filtfilt_or_fail(const SosCascade<kCapacity>& sos, const std::vector<double>& x) {
    std::vector<double> y(x.size());
    std::vector<double> workspace(jacobid::sosfiltfilt_workspace_size(sos));
    EXPECT_EQ(jacobid::sosfiltfilt(sos, jacobid::Span<const double>(x.data(), x.size()), y, workspace),
              FilterStatus::Ok);
    return y;
}

class FiltfiltMatchesScipy : public ::testing::TestWithParam<FilterCase> {};

// With scipy's own coefficients, so the filter implementations are compared on their own.
TEST_P(FiltfiltMatchesScipy, SosfiltZiAndSosfiltfilt) {
    const FilterCase c = GetParam();
    const auto reference = run_scipy_baseline("filter " + describe_case(c) + " " + std::to_string(c.length) + " 7");
    const std::vector<double>& x = array_named(reference, "x");
    const auto sos = cascade_from_reference<kCapacity>(array_named(reference, "sos"));
    const double scale = max_abs(x);

    EXPECT_LE(max_abs_difference(sosfilt_from_rest(sos, x), array_named(reference, "sosfilt")),
              kSignalTolerance * scale);
    const std::vector<double>& zi = array_named(reference, "zi");
    EXPECT_LE(max_abs_difference(flatten(jacobid::sosfilt_zi(sos), sos.count), zi), kSignalTolerance * max_abs(zi));
    EXPECT_LE(max_abs_difference(filtfilt_or_fail(sos, x), array_named(reference, "sosfiltfilt")),
              kSignalTolerance * scale);
}

// Our design followed by our filter: the pipeline the identification uses.
TEST_P(FiltfiltMatchesScipy, DesignedButterworthFiltfilt) {
    const FilterCase c = GetParam();
    const auto reference = run_scipy_baseline("filter " + describe_case(c) + " " + std::to_string(c.length) + " 11");
    const std::vector<double>& x = array_named(reference, "x");
    SosCascade<kCapacity> sos;
    ASSERT_EQ(jacobid::butterworth_lowpass(c.order, c.cutoff_hz, c.sample_rate_hz, sos), FilterStatus::Ok);
    EXPECT_LE(max_abs_difference(filtfilt_or_fail(sos, x), array_named(reference, "sosfiltfilt")),
              kSignalTolerance * max_abs(x));
}

// The shortest signal sosfiltfilt accepts is padlen + 1 samples, and there the whole output is edge:
// scipy must agree on the boundary and on the values.
TEST_P(FiltfiltMatchesScipy, PadlenBoundaryAsScipy) {
    const FilterCase c = GetParam();
    SosCascade<kCapacity> sos;
    ASSERT_EQ(jacobid::butterworth_lowpass(c.order, c.cutoff_hz, c.sample_rate_hz, sos), FilterStatus::Ok);
    const std::size_t padlen = jacobid::sosfiltfilt_padlen(sos);
    const auto accepted = run_scipy_baseline("filtfilt_accepts " + describe_case(c) + " " + std::to_string(padlen) +
                                             "," + std::to_string(padlen + 1));
    EXPECT_EQ(array_named(accepted, "accepted"), (std::vector<double>{0.0, 1.0}));

    std::vector<double> too_short(padlen, 1.0);
    std::vector<double> y(padlen);
    std::vector<double> workspace(jacobid::sosfiltfilt_workspace_size(sos));
    EXPECT_EQ(jacobid::sosfiltfilt(sos, jacobid::Span<const double>(too_short.data(), padlen), y, workspace),
              FilterStatus::SignalTooShort);

    const auto reference = run_scipy_baseline("filter " + describe_case(c) + " " + std::to_string(padlen + 1) + " 3");
    const std::vector<double>& x = array_named(reference, "x");
    EXPECT_LE(max_abs_difference(filtfilt_or_fail(sos, x), array_named(reference, "sosfiltfilt")),
              kSignalTolerance * max_abs(x));
}

INSTANTIATE_TEST_SUITE_P(Butterworth, FiltfiltMatchesScipy,
                         ::testing::Values(FilterCase{6, 25.0, 1000.0, 3000},  // paper section III baseline
                                           FilterCase{4, 0.1, 2.0, 2000},      // paper: 0.1 * (fs / 2)
                                           FilterCase{8, 5.0, 1000.0, 4000},   // very low normalized cutoff
                                           FilterCase{3, 5.0, 1000.0, 1500},   // odd: shorter padlen
                                           FilterCase{5, 450.0, 1000.0, 500},  // odd order near Nyquist
                                           FilterCase{1, 100.0, 1000.0, 200}));

TEST(FiltfiltStreamingState, ScaledSteadyStateStartsWithoutTransient) {
    // sosfilt_zi's defining property: from zi * c, a constant input c gives the constant output H(1) c.
    SosCascade<kCapacity> sos;
    ASSERT_EQ(jacobid::chebyshev1_lowpass(7, 1.0, 30.0, 1000.0, sos), FilterStatus::Ok);
    const double level = -2.5;
    jacobid::SosFilterState<kCapacity> filter(sos);
    filter.reset(jacobid::sosfilt_zi(sos), level);
    for (int k = 0; k < 200; ++k) EXPECT_NEAR(filter.step(level), sos.dc_gain() * level, 1e-12);
}

TEST(FiltfiltStreamingState, ResetReturnsToRest) {
    SosCascade<kCapacity> sos;
    ASSERT_EQ(jacobid::butterworth_lowpass(4, 50.0, 1000.0, sos), FilterStatus::Ok);
    jacobid::SosFilterState<kCapacity> filter(sos);
    const double first_impulse_response = filter.step(1.0);
    for (int k = 0; k < 10; ++k) filter.step(3.0);
    filter.reset();
    EXPECT_EQ(filter.step(1.0), first_impulse_response);
    EXPECT_EQ(first_impulse_response, sos.sections[0][0]);  // b0 of the cascade: every other b0 is 1
}

TEST(Filtfilt, InPlaceEqualsOutOfPlace) {
    SosCascade<kCapacity> sos;
    ASSERT_EQ(jacobid::butterworth_lowpass(6, 25.0, 1000.0, sos), FilterStatus::Ok);
    std::vector<double> x;
    for (int k = 0; k < 500; ++k) x.push_back(1.0 + std::sin(0.05 * k) + 0.1 * std::sin(1.3 * k));
    const std::vector<double> out_of_place = filtfilt_or_fail(sos, x);
    std::vector<double> buffer = x;
    std::vector<double> workspace(jacobid::sosfiltfilt_workspace_size(sos));
    ASSERT_EQ(jacobid::sosfiltfilt(sos, jacobid::Span<const double>(buffer.data(), buffer.size()), buffer, workspace),
              FilterStatus::Ok);
    EXPECT_EQ(buffer, out_of_place);
}

TEST(Filtfilt, WorkspaceSizes) {
    SosCascade<kCapacity> sos;
    ASSERT_EQ(jacobid::butterworth_lowpass(8, 25.0, 1000.0, sos), FilterStatus::Ok);
    EXPECT_EQ(jacobid::sosfiltfilt_padlen(sos), 3u * (2u * 4u + 1u));  // no first-order section
    EXPECT_EQ(jacobid::sosfiltfilt_workspace_size(sos), jacobid::sosfiltfilt_max_workspace_size<kCapacity>());
    ASSERT_EQ(jacobid::butterworth_lowpass(7, 25.0, 1000.0, sos), FilterStatus::Ok);
    EXPECT_EQ(jacobid::sosfiltfilt_padlen(sos), 3u * (2u * 4u + 1u - 1u));  // one first-order section
    EXPECT_LT(jacobid::sosfiltfilt_workspace_size(sos), jacobid::sosfiltfilt_max_workspace_size<kCapacity>());
}

// Error paths: each status comes from the condition it names, and y is not written.
class FiltfiltErrors : public ::testing::Test {
protected:
    void SetUp() override {
        ASSERT_EQ(jacobid::butterworth_lowpass(4, 50.0, 1000.0, sos), FilterStatus::Ok);
        x.assign(100, 1.0);
        y.assign(100, kUntouched);
        workspace.assign(jacobid::sosfiltfilt_workspace_size(sos), 0.0);
    }
    FilterStatus run(const SosCascade<kCapacity>& cascade, std::size_t x_size, std::size_t y_size,
                     std::size_t workspace_size) {
        return jacobid::sosfiltfilt(cascade, jacobid::Span<const double>(x.data(), x_size),
                                    jacobid::Span<double>(y.data(), y_size),
                                    jacobid::Span<double>(workspace.data(), workspace_size));
    }
    void expect_y_untouched() const {
        for (double v : y) EXPECT_EQ(v, kUntouched);
    }
    static constexpr double kUntouched = 12345.0;
    SosCascade<kCapacity> sos;
    std::vector<double> x, y, workspace;
};

TEST_F(FiltfiltErrors, MalformedCascadeIsInvalidCascade) {
    SosCascade<kCapacity> too_many = sos;
    too_many.count = kCapacity + 1;
    EXPECT_EQ(run(too_many, 100, 100, workspace.size()), FilterStatus::InvalidCascade);
    SosCascade<kCapacity> unnormalized = sos;
    unnormalized.sections[1][3] = 2.0;  // a0 != 1: scipy raises as well
    EXPECT_EQ(run(unnormalized, 100, 100, workspace.size()), FilterStatus::InvalidCascade);
    expect_y_untouched();
}

TEST_F(FiltfiltErrors, OutputOfOtherSizeIsOutputSizeMismatch) {
    EXPECT_EQ(run(sos, 100, 99, workspace.size()), FilterStatus::OutputSizeMismatch);
    EXPECT_EQ(run(sos, 99, 100, workspace.size()), FilterStatus::OutputSizeMismatch);
    expect_y_untouched();
}

TEST_F(FiltfiltErrors, SignalNotLongerThanPadlenIsSignalTooShort) {
    const std::size_t padlen = jacobid::sosfiltfilt_padlen(sos);
    EXPECT_EQ(run(sos, padlen, padlen, workspace.size()), FilterStatus::SignalTooShort);
    EXPECT_EQ(run(sos, 0, 0, workspace.size()), FilterStatus::SignalTooShort);
    expect_y_untouched();
    EXPECT_EQ(run(sos, padlen + 1, padlen + 1, workspace.size()), FilterStatus::Ok);
}

TEST_F(FiltfiltErrors, WorkspaceBelowDocumentedSizeIsWorkspaceTooSmall) {
    EXPECT_EQ(run(sos, 100, 100, workspace.size() - 1), FilterStatus::WorkspaceTooSmall);
    EXPECT_EQ(run(sos, 100, 100, 0), FilterStatus::WorkspaceTooSmall);
    expect_y_untouched();
    EXPECT_EQ(run(sos, 100, 100, workspace.size()), FilterStatus::Ok);
}

TEST(FiltfiltFilterStatus, EveryValueHasItsOwnLine) {
    const FilterStatus all[] = {FilterStatus::Ok,
                                FilterStatus::InvalidOrder,
                                FilterStatus::CapacityExceeded,
                                FilterStatus::InvalidSampling,
                                FilterStatus::InvalidCutoff,
                                FilterStatus::InvalidRipple,
                                FilterStatus::InvalidCascade,
                                FilterStatus::InvalidFactor,
                                FilterStatus::OutputSizeMismatch,
                                FilterStatus::SignalTooShort,
                                FilterStatus::WorkspaceTooSmall};
    std::set<std::string> lines;
    for (FilterStatus status : all) {
        const std::string line = jacobid::describe(status);
        EXPECT_FALSE(line.empty());
        EXPECT_EQ(line.find('\n'), std::string::npos);
        lines.insert(line);
    }
    EXPECT_EQ(lines.size(), std::size(all));
    EXPECT_STREQ(jacobid::describe(static_cast<FilterStatus>(999)), "unknown filter status value");
}

}  // namespace
