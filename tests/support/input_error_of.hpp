// SPDX-License-Identifier: MIT
#pragma once
// The message of the InputError a call throws, or "(no error)": how the reader tests compare messages byte
// for byte.
#include <functional>
#include <string>

#include "core/errors.hpp"

namespace jacobid::test {

inline std::string input_error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace jacobid::test
