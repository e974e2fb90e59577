// SPDX-License-Identifier: MIT
#include "signal/fftw_planner.hpp"

namespace jacobid::signal {

std::mutex& fftw_planner_mutex() {
    static std::mutex m;
    return m;
}

}  // namespace jacobid::signal
