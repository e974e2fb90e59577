// SPDX-License-Identifier: MIT
#pragma once
// Compile-time bounds of the firmware (fixed-size storage, nothing allocated after start-up), in one header
// that the configuration, the cycle and the trajectory player share.
#include <cstddef>

namespace jacobid::firmware {

constexpr std::size_t kMaxJoints = 8;
// Taps of the longest Jacobi window: 0.5 s at 1 kHz.
constexpr std::size_t kKernelCapacity = 512;
// Frames one cycle may drain; more stay queued for the next cycle (and are counted as backlog).
constexpr std::size_t kMaxFramesPerCycle = 64;

}  // namespace jacobid::firmware
