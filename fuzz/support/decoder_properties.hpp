// SPDX-License-Identifier: MIT
#pragma once
// The checks every device-profile fuzz target applies to each frame it feeds a configured decoder:
//  - a decoded frame (Ok) has a length a transport can deliver and leaves finite link-side values within the mapping's plausibility limits
//    (a generic profile's velocity-only frame is Ok without refreshing position or torque);
//  - any other outcome (not mine, short, out of range, malformed) leaves the joint state unchanged
//    (the profiles promise "a rejected frame changes nothing", joint_decoder_set.hpp).
#include <cmath>
#include <cstdio>
#include <cstring>

#include "can_fuzz_input.hpp"
#include "fuzz_check.hpp"
#include "jacobid/hal/joint_state.hpp"

namespace jacobid::fuzz {

inline bool same_state(const hal::JointState& a, const hal::JointState& b) {
    // Compared bit for bit: NaN must not sneak in unnoticed.
    return std::memcmp(&a.position, &b.position, sizeof(double)) == 0 && std::memcmp(&a.velocity, &b.velocity, sizeof(double)) == 0 &&
           std::memcmp(&a.torque, &b.torque, sizeof(double)) == 0 && a.position_time_ns == b.position_time_ns &&
           a.torque_time_ns == b.torque_time_ns && a.position_age == b.position_age && a.torque_age == b.torque_age &&
           a.device_error == b.device_error && a.temperature_c == b.temperature_c && a.position_fresh == b.position_fresh &&
           a.torque_fresh == b.torque_fresh;
}

// Printed before a violated property aborts: the frame and the values, for the regression test.
inline void describe_failure(const hal::CanFrame& f, const hal::JointState& s, const hal::JointMapping& m) {
    std::fprintf(stderr, "frame id 0x%X len %u flags 0x%X data", static_cast<unsigned>(f.id), static_cast<unsigned>(f.len),
                 static_cast<unsigned>(f.flags));
    for (std::size_t i = 0; i < 8; ++i) std::fprintf(stderr, " %02X", static_cast<unsigned>(f.data[i]));
    std::fprintf(stderr, "\nstate position %.17g velocity %.17g torque %.17g\n", s.position, s.velocity, s.torque);
    std::fprintf(stderr, "mapping gear %.17g direction %.17g offset %.17g Kt %.17g max_v %.17g max_tau %.17g\n", m.gear_ratio, m.direction,
                 m.position_offset, m.torque_constant, m.max_abs_velocity, m.max_abs_torque);
}

template <typename Decoder>
void check_decode(Decoder& decoder, const hal::CanFrame& frame, hal::JointState& state, const hal::JointMapping& m) {
    const hal::JointState before = state;
    const hal::DecodeStatus status = decoder.decode(frame, state);
    const bool ok = status == hal::DecodeStatus::Ok;
    if (ok ? !(finite_state(state) && std::abs(state.velocity) <= m.max_abs_velocity && std::abs(state.torque) <= m.max_abs_torque)
           : !same_state(before, state)) {
        describe_failure(frame, state, m);
    }
    if (!ok) {
        JACOBID_FUZZ_CHECK(same_state(before, state), "a rejected frame changed the joint state");
        return;
    }
    JACOBID_FUZZ_CHECK(finite_state(state), "a decoded frame produced a non-finite joint value");
    JACOBID_FUZZ_CHECK(frame.len <= (frame.fd() ? hal::kCanFdMaxDataLength : hal::kCanMaxDataLength), "decoded a frame of impossible length");
    JACOBID_FUZZ_CHECK(std::abs(state.velocity) <= m.max_abs_velocity, "decoded velocity beyond max_abs_velocity");
    JACOBID_FUZZ_CHECK(std::abs(state.torque) <= m.max_abs_torque, "decoded torque beyond max_abs_torque");
}

}  // namespace jacobid::fuzz
