// SPDX-License-Identifier: MIT
#pragma once
// The per-cycle demultiplexer: a fixed set of joints, each with its device profile, fed with the frames
// a transport drained; keeps every joint's JointState and the decode counters.
//
// Firmware cycle:
//     set.begin_cycle();                          // age states, clear per-cycle flags
//     auto r = transport.drain(frames);           // non-blocking
//     set.dispatch(Span<const CanFrame>(frames.data(), r.count));
//     ... read set.state(j) (use only !stale) ...
// A frame goes to the first joint whose decoder does not answer NotMine (the decoder's own test, the
// only one: docs/profiles.md); if none does it is counted as unknown id. route() also says which joint
// took it, for the firmware's duplicate detection. A claimed frame that fails its checks is counted by
// reason and flags that joint's decode_error; it never changes the state. Nothing allocates
// (std::variant holds values; profile dispatch: profile_registry.hpp).
#include <array>
#include <cstddef>
#include <cstdint>
#include <variant>

#include "jacobid/hal/can_frame.hpp"
#include "jacobid/hal/joint_state.hpp"
#include "jacobid/hal/profile_registry.hpp"
#include "jacobid/span.hpp"

namespace jacobid::hal {

struct DecoderSetConfigResult {
    ConfigStatus status = ConfigStatus::Ok;
    std::size_t joint = 0;  // first offending joint
};

// Where a frame went: the joint whose decoder claimed it (kNoJoint: nobody's) and what it answered.
struct RouteResult {
    static constexpr std::size_t kNoJoint = static_cast<std::size_t>(-1);
    DecodeStatus status = DecodeStatus::UnknownId;
    std::size_t joint = kNoJoint;
};

template <std::size_t MaxJoints>
class JointDecoderSet {
    static_assert(MaxJoints > 0, "a decoder set needs at least one joint");

public:
    // max_age: cycles a value may go without refresh before the joint is stale (0: every cycle).
    DecoderSetConfigResult configure(Span<const ProfileConfig> joints, std::uint32_t max_age = 0) noexcept {
        count_ = 0;
        if (joints.size() > MaxJoints) return {ConfigStatus::TooManyJoints, MaxJoints};
        for (std::size_t j = 0; j < joints.size(); ++j) {
            const ConfigStatus s = hal::configure(decoders_[j], joints[j]);
            if (s != ConfigStatus::Ok) return {s, j};
        }
        count_ = joints.size();
        max_age_ = max_age;
        counters_ = DecodeCounters{};
        for (auto& s : states_) s = JointState{};
        return {};
    }

    void begin_cycle() noexcept {
        for (std::size_t j = 0; j < count_; ++j) hal::begin_cycle(states_[j], max_age_);
    }

    RouteResult route(const CanFrame& f) noexcept {
        ++counters_.frames;
        for (std::size_t j = 0; j < count_; ++j) {
            const DecodeStatus s = hal::decode(decoders_[j], f, states_[j]);
            if (s == DecodeStatus::NotMine) continue;
            if (s == DecodeStatus::Ok) {
                ++counters_.decoded;
                update_stale(states_[j], max_age_);
            } else {
                count_rejection(s);
                states_[j].decode_error = true;
            }
            return {s, j};
        }
        ++counters_.rejected_unknown_id;
        return {};
    }
    DecodeStatus dispatch(const CanFrame& f) noexcept { return route(f).status; }

    // Dispatches every frame; returns how many were decoded.
    std::size_t dispatch(Span<const CanFrame> frames) noexcept {
        std::size_t ok = 0;
        for (const CanFrame& f : frames) ok += dispatch(f) == DecodeStatus::Ok ? 1u : 0u;
        return ok;
    }

    // Forget the unwrapping history (e.g. after a drive re-homed); states are kept until refreshed.
    void reset_unwrapping() noexcept {
        for (std::size_t j = 0; j < count_; ++j) hal::reset_unwrapping(decoders_[j]);
    }

    std::size_t joint_count() const noexcept { return count_; }
    const JointState& state(std::size_t j) const noexcept { return states_[j]; }
    Span<const JointState> states() const noexcept { return {states_.data(), count_}; }
    const DecodeCounters& counters() const noexcept { return counters_; }

private:
    void count_rejection(DecodeStatus s) noexcept {
        switch (s) {
            case DecodeStatus::Short: ++counters_.rejected_short; break;
            case DecodeStatus::OutOfRange: ++counters_.rejected_out_of_range; break;
            case DecodeStatus::UnknownId: ++counters_.rejected_unknown_id; break;
            default: ++counters_.rejected_malformed; break;
        }
    }

    std::array<AnyJointDecoder, MaxJoints> decoders_{};
    std::array<JointState, MaxJoints> states_{};
    DecodeCounters counters_{};
    std::size_t count_ = 0;
    std::uint32_t max_age_ = 0;
};

}  // namespace jacobid::hal
