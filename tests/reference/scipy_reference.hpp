// SPDX-License-Identifier: MIT
#pragma once
// Test-side helper: runs tests/reference/scipy_baseline.py with the python that has scipy
// (JACOBID_REFERENCE_PYTHON) and parses its output, one array per line "<name> <v0> <v1> ..." printed
// with %.17g, so the doubles arrive bit for bit. Also the comparisons the baseline tests share.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../support/run_command.hpp"
#include "jacobid/baseline/sos.hpp"

namespace jacobid::reference {

using ReferenceArrays = std::map<std::string, std::vector<double>>;

// JACOBID_TESTS_DIR is the tests/ folder of the source tree.
inline std::string scipy_baseline_script() { return std::string(JACOBID_TESTS_DIR) + "/reference/scipy_baseline.py"; }

// Formats a double so that python parses back the same double.
inline std::string exact(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

// Runs `scipy_baseline.py <arguments>`; throws (a test failure, with the script's stderr) if it fails.
inline ReferenceArrays run_scipy_baseline(const std::string& arguments) {
    const std::string command =
        std::string("\"") + JACOBID_REFERENCE_PYTHON + "\" \"" + scipy_baseline_script() + "\" " + arguments;
    const jacobid::test::CommandResult result = jacobid::test::run_command(command);
    if (result.exit_code != 0) throw std::runtime_error("reference script failed: " + command + "\n" + result.err);

    ReferenceArrays arrays;
    std::istringstream lines(result.out);
    for (std::string line; std::getline(lines, line);) {
        std::istringstream fields(line);
        std::string name;
        if (!(fields >> name)) continue;
        std::vector<double>& values = arrays[name];
        for (std::string number; fields >> number;) values.push_back(std::strtod(number.c_str(), nullptr));
    }
    return arrays;
}

inline const std::vector<double>& array_named(const ReferenceArrays& arrays, const std::string& name) {
    const auto found = arrays.find(name);
    if (found == arrays.end()) throw std::runtime_error("reference output has no array '" + name + "'");
    return found->second;
}

// Running maximum that lets a NaN through (std::max would drop it), so a NaN can never pass a bound.
inline double max_keeping_nan(double largest, double candidate) { return candidate <= largest ? largest : candidate; }

inline double max_abs(const std::vector<double>& values) {
    double largest = 0.0;
    for (double v : values) largest = max_keeping_nan(largest, std::abs(v));
    return largest;
}

// Largest |actual - expected|; infinite when the sizes differ, so a size error cannot pass a bound.
inline double max_abs_difference(const std::vector<double>& actual, const std::vector<double>& expected) {
    if (actual.size() != expected.size()) return INFINITY;
    double largest = 0.0;
    for (std::size_t i = 0; i < actual.size(); ++i)
        largest = max_keeping_nan(largest, std::abs(actual[i] - expected[i]));
    return largest;
}

// scipy's sos array (n_sections x 6, flattened) as a cascade; throws if it does not fit.
template <std::size_t MaxSections>
SosCascade<MaxSections> cascade_from_reference(const std::vector<double>& flat_sos) {
    if (flat_sos.size() % 6 != 0 || flat_sos.size() / 6 > MaxSections) throw std::runtime_error("bad sos array");
    SosCascade<MaxSections> cascade;
    cascade.count = flat_sos.size() / 6;
    for (std::size_t i = 0; i < flat_sos.size(); ++i) cascade.sections[i / 6][i % 6] = flat_sos[i];
    return cascade;
}

// Worst coefficient error of a designed cascade against scipy's sos array, relative to the largest
// coefficient of the same polynomial (b or a of the same section): a coefficient that is zero up to
// rounding (e.g. a1 of a pole pair on the imaginary axis) is judged on the polynomial's scale.
// Infinite when the section counts differ.
template <std::size_t MaxSections>
double sos_relative_error(const SosCascade<MaxSections>& actual, const std::vector<double>& expected_flat) {
    if (expected_flat.size() != 6 * actual.count) return INFINITY;
    double worst = 0.0;
    for (std::size_t section = 0; section < actual.count; ++section) {
        for (std::size_t first : {std::size_t{0}, std::size_t{3}}) {
            double scale = 0.0;
            for (std::size_t j = first; j < first + 3; ++j)
                scale = std::max(scale, std::abs(expected_flat[6 * section + j]));
            for (std::size_t j = first; j < first + 3; ++j) {
                const double error = std::abs(actual.sections[section][j] - expected_flat[6 * section + j]);
                worst = max_keeping_nan(worst, error / scale);
            }
        }
    }
    return worst;
}

}  // namespace jacobid::reference
