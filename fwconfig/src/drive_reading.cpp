// SPDX-License-Identifier: MIT
#include "drive_reading.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "jacobid/hal/profile_registry.hpp"

namespace jacobid::firmware {
namespace {

// The command as the drive reads it; fields the frames do not carry (or a frame the drive refuses) stay NaN.
hal::JointCommand as_read(const hal::ProfileConfig& joint, const hal::JointCommand& sent) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    hal::JointCommand read{sent.mode, nan, nan, nan, nan, nan};
    std::array<hal::CanFrame, hal::kMaxCommandFrames> frames{};
    const std::size_t n = hal::encode_command(joint, sent, frames.data());
    for (std::size_t f = 0; f < n; ++f) hal::decode_command(joint, sent.mode, frames[f], read);
    return read;
}

// Whether `value` saturates: the drive reads the same whether it is sent or pushed much further out, and
// that reading is off by more than 0.5 % of the value's scale. Quantization never gives both (pushing an
// encodable value out moves the reading; a value within a code of the edge reads within a code of itself).
bool saturates(const hal::ProfileConfig& joint, hal::JointCommand command, double hal::JointCommand::*field, double direction, double scale,
               double& carried) {
    const double value = command.*field;
    carried = as_read(joint, command).*field;
    if (std::isnan(carried)) return false;  // not sent at all
    command.*field = value + direction * (std::abs(value) + scale);
    const double further = as_read(joint, command).*field;
    return further == carried && std::abs(carried - value) > 0.005 * std::max(std::abs(value), scale);
}

}  // namespace

bool reads_position_commands(const hal::ProfileConfig& joint, double kp, double kd) {
    const hal::JointCommand read = as_read(joint, hal::JointCommand{hal::CommandMode::Position, 0.0, 0.0, 0.0, kp, kd});
    return read.mode == hal::CommandMode::Position;
}

std::optional<UncarriedLimit> uncarried_limit(const hal::ProfileConfig& joint, const PlaybackConfig& p, std::size_t j) {
    const double lo = p.position_min[j], hi = p.position_max[j], span = hi - lo, middle = 0.5 * (lo + hi);
    const hal::JointCommand at_rest{p.mode, middle, 0.0, 0.0, p.kp[j], p.kd[j]};
    double carried = 0.0;
    auto with = [&](double hal::JointCommand::*field, double value) {
        hal::JointCommand c = at_rest;
        c.*field = value;
        return c;
    };
    if (p.mode == hal::CommandMode::Position) {
        if (saturates(joint, with(&hal::JointCommand::position, lo), &hal::JointCommand::position, -1.0, span, carried)) return UncarriedLimit{"position", lo, carried};
        if (saturates(joint, with(&hal::JointCommand::position, hi), &hal::JointCommand::position, 1.0, span, carried)) return UncarriedLimit{"position", hi, carried};
        for (const double v : {-p.velocity_limit[j], p.velocity_limit[j]}) {
            if (saturates(joint, with(&hal::JointCommand::velocity, v), &hal::JointCommand::velocity, v < 0 ? -1.0 : 1.0, std::abs(v), carried)) {
                return UncarriedLimit{"velocity", v, carried};
            }
        }
        if (p.kp[j] > 0.0 && saturates(joint, at_rest, &hal::JointCommand::kp, 1.0, p.kp[j], carried)) return UncarriedLimit{"kp", p.kp[j], carried};
        if (p.kd[j] > 0.0 && saturates(joint, at_rest, &hal::JointCommand::kd, 1.0, p.kd[j], carried)) return UncarriedLimit{"kd", p.kd[j], carried};
    }
    for (const double t : {-p.torque_limit[j], p.torque_limit[j]}) {
        if (saturates(joint, with(&hal::JointCommand::torque, t), &hal::JointCommand::torque, t < 0 ? -1.0 : 1.0, std::abs(t), carried)) {
            return UncarriedLimit{"torque", t, carried};
        }
    }
    return std::nullopt;
}

}  // namespace jacobid::firmware
