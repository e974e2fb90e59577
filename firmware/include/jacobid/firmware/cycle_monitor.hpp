// SPDX-License-Identifier: MIT
#pragma once
// The contact monitor as the firmware cycle runs it (fw.yaml `monitor:`, docs/firmware.md "Contact
// monitor"): each published row's aligned estimates (q^, qd^ and tau of the bank, at the row's instant) go
// through the lib's momentum observer (external_torque.hpp) and contact detector (contact_detector.hpp).
// configure() builds the model from a MonitorModel (start-up, may allocate nothing but returns a reason);
// step() allocates nothing and never throws.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "jacobid/fwconfig/capacity.hpp"
#include "jacobid/fwconfig/monitor_config.hpp"
#include "jacobid/robot/contact_detector.hpp"
#include "jacobid/robot/external_torque.hpp"

namespace jacobid::firmware {

struct MonitorRow {
    std::array<double, kMaxJoints> external{};  // N.m: tau_ext per joint (0 before the first valid row)
    std::uint32_t over = 0;                     // bit j: joint j beyond its threshold in this row
    bool contact = false;                       // a contact confirmed in this row (persistence met)
    bool started = false;                       // this row came after the first valid one
};

class CycleMonitor {
public:
    static constexpr int N = static_cast<int>(kMaxJoints);
    using Joints = robot::JointVector<N>;

    CycleMonitor() noexcept = default;
    CycleMonitor(const CycleMonitor&) = delete;
    CycleMonitor& operator=(const CycleMonitor&) = delete;

    // "" or a one-line reason (the model's joint count differs, the chain is invalid, a gain <= 0 ...).
    std::string configure(const MonitorModel& model, std::size_t joints, double sample_period);
    bool enabled() const noexcept { return observer_.has_value(); }
    void disable() noexcept;

    // One aligned row. `valid`: the bank's estimates are valid (warm-up over); `trusted`: no joint of the
    // row is stale, undecodable or has a stale sample in its windows. The observer integrates every valid
    // row (its momentum balance needs them all); only trusted rows may raise a contact.
    const MonitorRow& step(const Joints& q, const Joints& qd, const Joints& tau, bool valid, bool trusted) noexcept;
    const MonitorRow& last() const noexcept { return row_; }
    // The observer's last estimate: per joint the external torque, the Coulomb band and whether it stands.
    const robot::ExternalTorqueEstimate<N>& estimate() const noexcept { return estimate_; }
    const robot::ContactDetector<N>& detector() const noexcept { return detector_; }

private:
    std::size_t joints_ = 0;
    // optional: the terms have no default state and the observer holds a reference to them; emplaced once
    // at start-up, in place (no heap).
    std::optional<robot::RigidBodyTerms<N>> terms_;
    std::optional<robot::MomentumObserver<N>> observer_;
    robot::ContactDetector<N> detector_{};
    robot::ExternalTorqueEstimate<N> estimate_{};
    MonitorRow row_{};
};

}  // namespace jacobid::firmware
