// SPDX-License-Identifier: MIT
#pragma once
// What every profile's JointDecoder shares: configure (validate, then keep the config and reset the
// unwrapper to the profile's wrap period), reset, and the commit rule of docs/profiles.md: a frame moves
// the position unwrapper only once it passed every check, so a rejected frame never counts a turn.
//
// The profile provides, in its own namespace (found by argument-dependent lookup):
//   ConfigStatus validate(const JointConfig&);       every config error, as a value
//   auto unwrap_period(const JointConfig&);           the Unwrapper's constructor argument (0: no wrap)
// Fixed size, no allocation, no exceptions: the decoders run in the firmware cycle (hal/ conventions).
#include <cmath>

#include "jacobid/hal/joint_state.hpp"

namespace jacobid::hal {

template <typename Config, typename Unwrapper>
class JointDecoderBase {
public:
    ConfigStatus configure(const Config& c) noexcept {
        const ConfigStatus s = validate(c);
        if (s == ConfigStatus::Ok) {
            config_ = c;
            unwrap_ = Unwrapper(unwrap_period(c));
        }
        return s;
    }
    const Config& config() const noexcept { return config_; }
    // Forget the unwrapping history (e.g. after the drive re-homed).
    void reset() noexcept { unwrap_.reset(); }

protected:
    // Unwraps `raw`, maps it with `to_link_position` and keeps the unwrapper's move only when the
    // result is finite. Call it after every other check of the frame. Returns false: OutOfRange.
    template <typename Raw, typename ToLinkPosition>
    bool commit_position(Raw raw, ToLinkPosition to_link_position, double& position) noexcept {
        Unwrapper next = unwrap_;
        position = to_link_position(next.update(raw));
        if (!std::isfinite(position)) return false;
        unwrap_ = next;
        return true;
    }

    Config config_{};
    Unwrapper unwrap_{unwrap_period(Config{})};
};

}  // namespace jacobid::hal
