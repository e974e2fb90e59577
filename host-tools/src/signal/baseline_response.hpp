// SPDX-License-Identifier: MIT
#pragma once
// Frequency response of the classic pipeline the paper compares against: a Butterworth low-pass run
// forward and backward (|H|^2, zero phase) followed by central Euler differences.
#include <complex>
#include <string>

#include "jacobid/baseline/butterworth.hpp"
#include "jacobid/baseline/sos.hpp"

namespace jacobid::signal {

constexpr std::size_t kMaxButterworthSections = 8;  // order <= 16
using ButterworthSos = SosCascade<kMaxButterworthSections>;

struct ButterworthEuler {
    int order = 4;
    double cutoff_hz = 0.0;
    ButterworthSos sos{};
};

// Parses "ORDER:CUTOFF_HZ" (e.g. "6:25") and designs the filter for sample period ts; InputError names
// `option_name` and what is wrong.
ButterworthEuler parse_butterworth_spec(const std::string& spec, const std::string& option_name, double ts);

// Designs or throws InputError naming `what` (an option or a YAML key).
ButterworthSos design_butterworth_or_throw(int order, double cutoff_hz, double ts, const std::string& what);

// H(e^{i w}) of a cascade of second-order sections at frequency f.
std::complex<double> sos_response(const ButterworthSos& sos, double ts, double f);

// Response of forward-backward filtering followed by the central difference of derivative `order`
// (0: none, 1: (x[k+1]-x[k-1])/2Ts, 2: (x[k+1]-2x[k]+x[k-1])/Ts^2).
std::complex<double> butterworth_euler_response(const ButterworthEuler& filter, int order, double ts, double f);

}  // namespace jacobid::signal
