// SPDX-License-Identifier: MIT
#pragma once
// Per-sample contact decision on an external-torque estimate (external_torque.hpp; docs/method.md,
// "External torque and contact detection"). Joint j is in contact when
//     moving:   |tau_ext_j| > moving_j,
//     standing: |tau_ext_j| > band_j + standing_j,
// the thresholds calibrated from contact-free logs at a stated false-alarm rate (`jacobid monitor
// calibrate`). At standstill the joint's Coulomb band holds any torque inside it, so a torque inside the band
// is friction, not contact: the standing threshold is the margin beyond the band. Allocation-free.
#include <array>
#include <cmath>
#include <cstdint>

#include "jacobid/robot/external_torque.hpp"

namespace jacobid::robot {

struct JointThresholds {
    double moving = 0.0;    // N.m
    double standing = 0.0;  // N.m beyond the Coulomb band
};

template <int N>
class ContactDetector {
public:
    void set_joint(int j, const JointThresholds& t) noexcept { thresholds_[static_cast<std::size_t>(j)] = t; }
    const JointThresholds& joint(int j) const noexcept { return thresholds_[static_cast<std::size_t>(j)]; }

    // The threshold joint j's estimate is compared with in this sample.
    double threshold(const ExternalTorqueEstimate<N>& e, int j) const noexcept {
        const auto js = static_cast<std::size_t>(j);
        return e.standing[js] ? e.band[j] + thresholds_[js].standing : thresholds_[js].moving;
    }

    // Bit j set: joint j is in contact (joints beyond `joints` are not looked at).
    std::uint32_t detect(const ExternalTorqueEstimate<N>& e, int joints) const noexcept {
        std::uint32_t mask = 0;
        for (int j = 0; j < joints && j < 32; ++j) {
            if (std::abs(e.external[j]) > threshold(e, j)) mask |= 1u << static_cast<unsigned>(j);
        }
        return mask;
    }

    // Persistence: a contact counts once some joint has been over its threshold for `samples` consecutive
    // samples (1: at once). A glitch of one sample in the log (a resampled timing jump) is no contact, at the
    // price of samples - 1 periods of delay.
    void set_confirm(int samples) noexcept { confirm_ = samples < 1 ? 1 : samples; }
    int confirm() const noexcept { return confirm_; }
    // Feeds one sample's detect() mask; true once the contact is confirmed (and while it lasts).
    bool confirmed(std::uint32_t mask) noexcept {
        run_ = mask != 0 ? (run_ < confirm_ ? run_ + 1 : confirm_) : 0;
        return run_ >= confirm_;
    }
    void reset() noexcept { run_ = 0; }

private:
    std::array<JointThresholds, N> thresholds_{};
    int confirm_ = 1;
    int run_ = 0;
};

}  // namespace jacobid::robot
