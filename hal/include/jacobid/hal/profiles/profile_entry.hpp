// SPDX-License-Identifier: MIT
#pragma once
// What every profile header includes, and the shape of its registry entry (hal/profile_registry.hpp).
//
// A profile header defines, in its own namespace, next to its JointConfig (found by argument-dependent
// lookup, so the registry never names a profile):
//   ConfigStatus validate(const JointConfig&)
//   JointDecoder (a JointDecoderBase) whose decode() alone decides whether a frame is the joint's
//   std::size_t encode_telemetry(const JointConfig&, q, qd, tau, CanFrame* out)   drive side (sim-can)
//   std::size_t encode_command(const JointConfig&, const JointCommand&, CanFrame* out)
//   DecodeStatus decode_command(const JointConfig&, CommandMode drive_mode, const CanFrame&, JointCommand&)
//                                                               drive side: a command as the device reads it
// and, when fw.yaml offers it (kInFirmwareConfig):
//   void apply_firmware_defaults(JointConfig&, std::size_t joint_index)
//   template <class Fields> void read_config(Fields&, JointConfig&)   (mapping_fields.hpp)
//   const char* config_key_of(const JointConfig&, ConfigStatus)       the key a status is about
// plus `struct Profile : ProfileEntry<...> { static constexpr const char* kName = "..."; };`.
#include <cstddef>

#include "jacobid/hal/byte_codec.hpp"
#include "jacobid/hal/can_frame.hpp"
#include "jacobid/hal/joint_command.hpp"
#include "jacobid/hal/joint_state.hpp"
#include "jacobid/hal/profiles/joint_decoder_base.hpp"
#include "jacobid/hal/profiles/mapping_fields.hpp"
#include "jacobid/hal/profiles/plausibility.hpp"
#include "jacobid/hal/unwrap.hpp"

namespace jacobid::hal {

template <typename JointConfig, typename JointDecoder, std::size_t TelemetryFrames, bool InFirmwareConfig>
struct ProfileEntry {
    using Config = JointConfig;
    using Decoder = JointDecoder;
    static constexpr std::size_t kTelemetryFrames = TelemetryFrames;  // frames per sample, drive side
    static constexpr bool kInFirmwareConfig = InFirmwareConfig;       // `profile: <kName>` in fw.yaml
};

}  // namespace jacobid::hal
