// SPDX-License-Identifier: MIT
#include "sim/can_player.hpp"

#include <variant>

namespace jacobid::sim {

CanPlayer::CanPlayer(hal::CanTransport& can, std::vector<hal::ProfileConfig> joints) : can_(can), joints_(std::move(joints)) {}

std::size_t CanPlayer::encode(std::size_t joint, double q, double qd, double tau, hal::CanFrame* out) const {
    const hal::ProfileConfig& p = joints_[joint];
    if (const auto* m = std::get_if<hal::mit::JointConfig>(&p)) {
        hal::mit::encode_reply(*m, q, qd, tau, out[0], m->require_status);
        return 1;
    }
    if (const auto* c = std::get_if<hal::cia402::JointConfig>(&p)) {
        hal::cia402::encode_tpdo(*c, q, tau, out[0]);
        return 1;
    }
    if (const auto* o = std::get_if<hal::odrive::JointConfig>(&p)) {
        hal::odrive::encode_encoder_estimates(*o, q, qd, out[0]);
        hal::odrive::encode_iq(*o, tau, out[1]);
        return 2;
    }
    return 0;  // generic layouts: no simulator encoder wired (the firmware config does not offer them)
}

std::size_t CanPlayer::send(const double* q, const double* qd, const double* tau) {
    ++counters_.samples;
    std::size_t sent = 0;
    hal::CanFrame frames[2];
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
