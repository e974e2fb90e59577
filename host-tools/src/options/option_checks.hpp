// SPDX-License-Identifier: MIT
#pragma once
// Checks of numeric command-line values, shared by every command.
//
// The validators run inside CLI11 on the text of the value, as the command line is read, so a value that is
// not a finite number, out of its range or not whole is refused with the option's name before any command
// runs ("--fmax: expected a finite number > 0, got 'nan'"), instead of being silently replaced by a default
// or reaching the computation. Values left at their defaults are not checked (the defaults are valid).
// CLI11 applies a validator to each item of a list option (--torque-noise 0.1,0.2).
//
// refuse_oversized() bounds the sizes that follow from several values (samples = duration x rate ...)
// before anything is allocated, and says what the request would cost.
#include <string>

#include <CLI/Error.hpp>  // Validators.hpp needs it first
#include <CLI/Validators.hpp>

namespace jacobid::options {

// Any finite number.
CLI::Validator finite_number();
// A finite number > 0.
CLI::Validator positive_number();
// A finite number >= 0.
CLI::Validator non_negative_number();
// A finite number in [low, high].
CLI::Validator number_in(double low, double high);
// A finite number in (low, high) (both ends excluded).
CLI::Validator number_between(double low, double high);
// A whole number (no fraction, no exponent) in [low, high]; for counts, orders and seeds.
CLI::Validator whole_number_in(double low, double high);
// A whole number >= low (up to 2^64 - 1, the largest seed).
CLI::Validator whole_number_from(double low);

// A file or folder path: not empty ('' used to mean "not given": --robot '' simulated the default robot) and,
// unless `dash_is_standard_output` (the option writes '-' to standard output), not '-' (simulate -o - wrote a
// file named '-').
CLI::Validator file_path(bool dash_is_standard_output = false);

// InputError unless `count` (of `unit`, e.g. "log samples") is at most `limit`; the message starts with
// `request` (the options and values that give the count), states the count and about `bytes_per_unit` x
// count bytes (left out when 0: a cost in time), and ends with `remedy` (which option to lower). Call it before allocating or running.
void refuse_oversized(const std::string& request, double count, double limit, const std::string& unit, double bytes_per_unit,
                      const std::string& remedy);

// "1.5 GB", "340 MB", "12 kB": a byte count for messages.
std::string describe_bytes(double bytes);

}  // namespace jacobid::options
