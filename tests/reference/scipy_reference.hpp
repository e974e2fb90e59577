// SPDX-License-Identifier: MIT
#pragma once
// Test-side helper: runs tests/reference/scipy_baseline.py with the python that has scipy
// (JACOBID_REFERENCE_PYTHON) and parses its output, one array per line "<name> <v0> <v1> ..." printed
// with %.17g, so the doubles arrive bit for bit. Also the comparisons the baseline tests share.
//
// JACOBID_REFERENCE_CACHE (a folder; scripts/run-tests.sh sets a fresh one per run): scipy's output is kept
// there, so the sanitizer run and the aarch64 and armhf unit tests under qemu-user read what the native run
// computed instead of starting python and importing scipy again for each case (about 1 s each; 80 cases under
// qemu-user). The key is the script's text and its arguments, hashed with FNV-1a (the same on every
// architecture, unlike std::hash), and the entry repeats them, so a collision reads as a miss. Unset: every
// call runs the script.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "../support/file_text.hpp"
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

namespace detail {

using jacobid::test::file_text;

inline std::uint64_t fnv1a(const std::string& text) {
    std::uint64_t hash = 14695981039346656037ull;
    for (unsigned char c : text) hash = (hash ^ c) * 1099511628211ull;
    return hash;
}

// The script's output for `arguments`, from JACOBID_REFERENCE_CACHE when it holds it (see the top).
inline std::string scipy_output(const std::string& arguments) {
    const std::string command =
        std::string("\"") + JACOBID_REFERENCE_PYTHON + "\" \"" + scipy_baseline_script() + "\" " + arguments;
    const char* cache = std::getenv("JACOBID_REFERENCE_CACHE");
    std::string key;
    std::filesystem::path entry;
    if (cache != nullptr && *cache != '\0') {
        key = file_text(scipy_baseline_script()) + "\n--arguments: " + arguments + "\n";
        char name[32];
        std::snprintf(name, sizeof name, "%016llx", static_cast<unsigned long long>(fnv1a(key)));
        entry = std::filesystem::path(cache) / name;
        const std::string kept = file_text(entry);
        if (kept.size() > key.size() && kept.compare(0, key.size(), key) == 0) return kept.substr(key.size());
    }
    const jacobid::test::CommandResult result = jacobid::test::run_command(command);
    if (result.exit_code != 0) throw std::runtime_error("reference script failed: " + command + "\n" + result.err);
    if (!entry.empty()) {
        // Written whole under a name of this process's, then renamed: a reader never sees half an entry.
        std::error_code ignored;
        std::filesystem::create_directories(entry.parent_path(), ignored);
        const std::filesystem::path part = entry.string() + "." + std::to_string(::getpid());
        std::ofstream(part, std::ios::binary) << key << result.out;
        std::filesystem::rename(part, entry, ignored);
    }
    return result.out;
}

}  // namespace detail

// Runs `scipy_baseline.py <arguments>`; throws (a test failure, with the script's stderr) if it fails.
inline ReferenceArrays run_scipy_baseline(const std::string& arguments) {
    ReferenceArrays arrays;
    std::istringstream lines(detail::scipy_output(arguments));
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
