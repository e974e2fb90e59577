// SPDX-License-Identifier: MIT
#pragma once
// Turns fuzzer bytes into what a device profile sees: a joint mapping and a stream of CAN frames.
//
// Parameters that only scale results (gear ratio, limits) are drawn mostly from a few realistic values
// and sometimes from the whole double range (including NaN, Inf, 0, negative), so that both the
// decode path of valid configurations and the rejection of invalid ones are reached quickly.
#include <fuzzer/FuzzedDataProvider.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "jacobid/hal/can_frame.hpp"
#include "jacobid/hal/joint_state.hpp"

namespace jacobid::fuzz {

// A double from `typical`, or (one time in eight) any bit pattern.
template <std::size_t N>
double pick_double(FuzzedDataProvider& in, const std::array<double, N>& typical) {
    if (in.ConsumeIntegralInRange<int>(0, 7) == 0) return in.ConsumeFloatingPoint<double>();
    return in.PickValueInArray(typical);
}

inline hal::JointMapping consume_mapping(FuzzedDataProvider& in) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    hal::JointMapping m;
    m.gear_ratio = pick_double(in, std::array<double, 5>{1.0, 4.0, -9.0, 0.5, 100.0});
    m.direction = pick_double(in, std::array<double, 2>{1.0, -1.0});
    m.position_offset = pick_double(in, std::array<double, 3>{0.0, 1.5, -3.0});
    m.torque_constant = pick_double(in, std::array<double, 3>{0.083, 1.0, 0.0});
    m.max_abs_velocity = pick_double(in, std::array<double, 3>{inf, 50.0, 1.0});
    m.max_abs_torque = pick_double(in, std::array<double, 3>{inf, 100.0, 1.0});
    return m;
}

// One frame whose id is `id` most of the time (so that the joint claims it) and anything otherwise.
inline hal::CanFrame consume_frame(FuzzedDataProvider& in, std::uint32_t id, bool extended) {
    hal::CanFrame f;
    const bool any_id = in.ConsumeIntegralInRange<int>(0, 15) == 0;
    f.id = any_id ? in.ConsumeIntegral<std::uint32_t>() : id;
    f.flags = in.ConsumeIntegralInRange<int>(0, 7) == 0 ? in.ConsumeIntegral<std::uint8_t>()
                                                        : static_cast<std::uint8_t>(extended ? hal::kCanExtended : 0);
    // Any length byte, including the impossible ones (> 64): a decoder must not read past the payload.
    f.len = in.ConsumeIntegralInRange<int>(0, 7) == 0 ? in.ConsumeIntegral<std::uint8_t>()
                                                      : in.ConsumeIntegralInRange<std::uint8_t>(0, 8);
    for (auto& b : f.data) b = in.ConsumeIntegral<std::uint8_t>();
    f.timestamp_ns = in.ConsumeIntegral<std::int64_t>();
    return f;
}

// What every profile promises for a frame it decoded: finite link-side values within the plausibility
// limits, and flags saying what was refreshed.
inline bool finite_state(const hal::JointState& s) {
    return std::isfinite(s.position) && std::isfinite(s.velocity) && std::isfinite(s.torque);
}

}  // namespace jacobid::fuzz
