// SPDX-License-Identifier: MIT
#pragma once
// FFTW's planner (plan creation and destruction) is not thread-safe; executing an existing plan is. Every
// fftw_plan_* and fftw_destroy_plan of the host tools holds this one lock, so that identifications may run
// on several threads at once (jacobid montecarlo).
#include <mutex>

namespace jacobid::signal {

std::mutex& fftw_planner_mutex();

}  // namespace jacobid::signal
