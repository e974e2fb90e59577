// SPDX-License-Identifier: MIT
#include "sim/can_player.hpp"


namespace jacobid::sim {

CanPlayer::CanPlayer(hal::CanTransport& can, std::vector<hal::ProfileConfig> joints) : can_(can), joints_(std::move(joints)) {}

// The profile's own drive-side encoder, through the registry (hal/profile_registry.hpp): the frames the
// firmware decodes with the same profile's decoder.
std::size_t CanPlayer::encode(std::size_t joint, double q, double qd, double tau, hal::CanFrame* out) const {
    return hal::encode_telemetry(joints_[joint], q, qd, tau, out);
}

std::size_t CanPlayer::send(const double* q, const double* qd, const double* tau) {
    ++counters_.samples;
    std::size_t sent = 0;
    hal::CanFrame frames[hal::kMaxTelemetryFrames];
    for (std::size_t j = 0; j < joints_.size(); ++j) {
        const std::size_t n = encode(j, q[j], qd[j], tau[j], frames);
        for (std::size_t i = 0; i < n; ++i) {
            const hal::CanStatus s = can_.send(frames[i]);
            if (s == hal::CanStatus::Ok) {
                ++sent;
            } else {
                ++counters_.send_failures;
                last_error_ = s;
            }
        }
    }
    counters_.frames_sent += sent;
    return sent;
}

}  // namespace jacobid::sim
