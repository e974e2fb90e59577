// SPDX-License-Identifier: MIT
#pragma once
// The simulator's motor drivers on a CAN bus: each sample of the closed-loop simulation (link-side q, qd,
// tau per joint) becomes the frames the joint's device would send, in its profile (MIT reply, CiA 402
// TPDO, ODrive encoder estimates + Iq, generic signals), encoded by the profile's own drive-side encoder
// through the registry (hal/profile_registry.hpp, docs/profiles.md). The bus is any
// CanTransport: SocketCAN for `jacobid sim-can`, a VirtualCanBus endpoint for in-process tests.
//
// The profile's own quantization is the measurement model here (MIT: 16-bit position, 12-bit effort):
// run the simulator without encoder quantization, so the resolution on the wire is the device's.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "jacobid/hal/can_transport.hpp"
#include "jacobid/hal/joint_decoder_set.hpp"

namespace jacobid::sim {

struct CanPlayerCounters {
    std::uint64_t samples = 0;
    std::uint64_t frames_sent = 0;
    std::uint64_t send_failures = 0;  // transport refused (TxQueueFull, I/O error): the frame is lost
};

class CanPlayer {
public:
    // One profile config per joint, in joint order (the same configs the firmware decodes with).
    CanPlayer(hal::CanTransport& can, std::vector<hal::ProfileConfig> joints);

    // Frames of one sample: link-side position (rad), velocity (rad/s) and torque (N.m) of every joint.
    // Returns the number of frames the transport accepted.
    std::size_t send(const double* q, const double* qd, const double* tau);

    // The frames of joint j for a sample, without sending (1 for MIT and CiA 402, 2 for ODrive, up to
    // hal::kMaxTelemetryFrames); `out` holds that many.
    std::size_t encode(std::size_t joint, double q, double qd, double tau, hal::CanFrame* out) const;

    std::size_t joint_count() const { return joints_.size(); }
    const CanPlayerCounters& counters() const { return counters_; }
    hal::CanStatus last_error() const { return last_error_; }

private:
    hal::CanTransport& can_;
    std::vector<hal::ProfileConfig> joints_;
    CanPlayerCounters counters_;
    hal::CanStatus last_error_ = hal::CanStatus::Ok;
};

}  // namespace jacobid::sim
