// SPDX-License-Identifier: MIT
#pragma once
// The host tools' error contract, shared by every module (io/, robot/, identify/, signal/, sim/, stream/,
// diagnose/) and by the command line that reports it.
//
// Bad input (a file, a parameter, data that cannot be used) is thrown as InputError with a one-line message
// that names the file, line, column or parameter; the command line prints it as
// "jacobid <command>: error: <message>" and exits with kExitInputError. Anything else that escapes is a bug
// or an environment problem and exits with kExitInternalError.
#include <stdexcept>

namespace jacobid {

constexpr int kExitOk = 0;
constexpr int kExitInputError = 2;     // bad file, bad parameter, data that cannot be used
constexpr int kExitInternalError = 3;  // a bug or an environment problem (e.g. gnuplot missing)

struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace jacobid
