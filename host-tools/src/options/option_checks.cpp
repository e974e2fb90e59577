// SPDX-License-Identifier: MIT
#include "options/option_checks.hpp"

#include <fmt/core.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "core/errors.hpp"

namespace jacobid::options {
namespace {

// The accepted values of one option: a finite number in a range whose ends may be excluded, whole or not.
struct NumberRule {
    double low = -std::numeric_limits<double>::infinity();
    double high = std::numeric_limits<double>::infinity();
    bool low_excluded = false;
    bool high_excluded = false;
    bool whole = false;
};

// "a finite number > 0", "a whole number in [0, 3]", ... (what the message says was expected).
std::string describe(const NumberRule& r) {
    std::string s = r.whole ? "a whole number" : "a finite number";
    const bool has_low = std::isfinite(r.low), has_high = std::isfinite(r.high) && r.high < 1e18;
    if (has_low && has_high) {
        s += fmt::format(" in {}{:g}, {:g}{}", r.low_excluded ? '(' : '[', r.low, r.high, r.high_excluded ? ')' : ']');
    } else if (has_low) {
        s += fmt::format(" {} {:g}", r.low_excluded ? ">" : ">=", r.low);
    } else if (has_high) {
        s += fmt::format(" {} {:g}", r.high_excluded ? "<" : "<=", r.high);
    }
    return s;
}

// Digits with an optional sign and nothing else: what an integer option accepts (no "1e3", no "2.0").
bool is_whole_text(const std::string& text) {
    std::size_t i = (!text.empty() && (text[0] == '+' || text[0] == '-')) ? 1 : 0;
    if (i == text.size()) return false;
    for (; i < text.size(); ++i) {
        if (!std::isdigit(static_cast<unsigned char>(text[i]))) return false;
    }
    return true;
}

CLI::Validator number_validator(const NumberRule& rule) {
    const std::string expected = describe(rule);
    return CLI::Validator(
        [rule, expected](std::string& text) -> std::string {
            const std::string wrong = fmt::format("expected {}, got '{}'", expected, text);
            if (rule.whole && !is_whole_text(text)) return wrong;
            char* end = nullptr;
            // long double holds every 64-bit integer exactly on the supported targets (x86-64, aarch64).
            const long double value = std::strtold(text.c_str(), &end);
            if (text.empty() || *end != '\0' || !std::isfinite(value)) return wrong;
            const auto low = static_cast<long double>(rule.low), high = static_cast<long double>(rule.high);
            if (value < low || (rule.low_excluded && value == low)) return wrong;
            if (value > high || (rule.high_excluded && value == high)) return wrong;
            return {};
        },
        expected);
}

}  // namespace

CLI::Validator finite_number() { return number_validator({}); }

CLI::Validator positive_number() {
    NumberRule r;
    r.low = 0.0;
    r.low_excluded = true;
    return number_validator(r);
}

CLI::Validator non_negative_number() {
    NumberRule r;
    r.low = 0.0;
    return number_validator(r);
}

CLI::Validator number_in(double low, double high) {
    NumberRule r;
    r.low = low;
    r.high = high;
    return number_validator(r);
}

CLI::Validator number_between(double low, double high) {
    NumberRule r;
    r.low = low;
    r.high = high;
    r.low_excluded = r.high_excluded = true;
    return number_validator(r);
}

CLI::Validator whole_number_in(double low, double high) {
    NumberRule r;
    r.low = low;
    r.high = high;
    r.whole = true;
    return number_validator(r);
}

CLI::Validator whole_number_from(double low) {
    NumberRule r;
    r.low = low;
    r.high = 18446744073709551615.0;  // 2^64 - 1 (rounds to 2^64 as a double; long double compares exactly)
    r.whole = true;
    return number_validator(r);
}

CLI::Validator file_path(bool dash_is_standard_output) {
    const std::string expected = dash_is_standard_output ? "a file path or '-' (standard output)" : "a file path";
    return CLI::Validator(
        [dash_is_standard_output, expected](std::string& text) -> std::string {
            if (text.empty()) return fmt::format("expected {}, got ''", expected);
            if (text == "-" && !dash_is_standard_output) return "expected a file path, got '-' (this option does not read or write standard input/output)";
            return {};
        },
        dash_is_standard_output ? "FILE|-" : "FILE");
}

std::string describe_bytes(double bytes) {
    const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB", "EB"};
    int u = 0;
    while (bytes >= 1000.0 && u < 6) {
        bytes /= 1000.0;
        ++u;
    }
    return fmt::format("{:.3g} {}", bytes, units[u]);
}

void refuse_oversized(const std::string& request, double count, double limit, const std::string& unit, double bytes_per_unit,
                      const std::string& remedy) {
    if (count <= limit) return;
    const std::string cost = bytes_per_unit > 0.0 ? fmt::format(" (about {})", describe_bytes(count * bytes_per_unit)) : std::string();
    throw InputError(fmt::format("{}: {:.3g} {}{}, more than the {:g} this command accepts; {}", request, count, unit, cost, limit, remedy));
}

}  // namespace jacobid::options
