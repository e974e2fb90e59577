// SPDX-License-Identifier: MIT
#include "signal/baseline_response.hpp"

#include <fmt/core.h>

#include <cmath>

#include "core/errors.hpp"

namespace jacobid::signal {

ButterworthSos design_butterworth_or_throw(int order, double cutoff_hz, double ts, const std::string& what) {
    ButterworthSos sos;
    const FilterStatus s = butterworth_lowpass(order, cutoff_hz, 1.0 / ts, sos);
    if (s != FilterStatus::Ok) {
        throw InputError(fmt::format("{}: Butterworth order {} cutoff {} Hz at {} Hz sampling: {}", what, order, cutoff_hz, 1.0 / ts, describe(s)));
    }
    return sos;
}

ButterworthEuler parse_butterworth_spec(const std::string& spec, const std::string& option_name, double ts) {
    const std::size_t colon = spec.find(':');
    ButterworthEuler b;
    try {
        if (colon == std::string::npos) throw std::invalid_argument(spec);
        std::size_t used = 0;
        b.order = std::stoi(spec.substr(0, colon), &used);
        if (used != colon) throw std::invalid_argument(spec);
        const std::string cutoff = spec.substr(colon + 1);
        b.cutoff_hz = std::stod(cutoff, &used);
        if (used != cutoff.size()) throw std::invalid_argument(spec);
    } catch (const std::exception&) {
        throw InputError(fmt::format("{}: expected ORDER:CUTOFF_HZ (e.g. 6:25), got '{}'", option_name, spec));
    }
    b.sos = design_butterworth_or_throw(b.order, b.cutoff_hz, ts, option_name);
    return b;
}

std::complex<double> sos_response(const ButterworthSos& sos, double ts, double f) {
    const std::complex<double> z1 = std::polar(1.0, -2.0 * M_PI * f * ts);  // z^-1
    const std::complex<double> z2 = z1 * z1;
    std::complex<double> h = 1.0;
    for (std::size_t i = 0; i < sos.count; ++i) {
        const auto& s = sos.sections[i];
        h *= (s[0] + s[1] * z1 + s[2] * z2) / (s[3] + s[4] * z1 + s[5] * z2);
    }
    return h;
}

std::complex<double> butterworth_euler_response(const ButterworthEuler& filter, int order, double ts, double f) {
    const double magnitude_squared = std::norm(sos_response(filter.sos, ts, f));  // forward-backward: |H|^2, phase 0
    const double w = 2.0 * M_PI * f * ts;
    std::complex<double> difference = 1.0;
    if (order == 1) difference = std::complex<double>(0.0, std::sin(w) / ts);
    if (order == 2) difference = (2.0 * std::cos(w) - 2.0) / (ts * ts);
    if (order >= 3) difference = std::pow(std::complex<double>(0.0, std::sin(w) / ts), order);
    return magnitude_squared * difference;
}

}  // namespace jacobid::signal
