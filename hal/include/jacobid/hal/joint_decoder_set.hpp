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
// A frame goes to the first joint whose profile claims it (CAN id, and data[0] for MIT); if none does it
// is counted as unknown id. A claimed frame that fails its checks is counted by reason and flags that
// joint's decode_error; it never changes the state. Nothing allocates (std::variant holds values).
#include <array>
#include <cstddef>
#include <cstdint>
#include <variant>

#include "jacobid/hal/can_frame.hpp"
#include "jacobid/hal/joint_state.hpp"
#include "jacobid/hal/profiles/cia402.hpp"
#include "jacobid/hal/profiles/generic.hpp"
#include "jacobid/hal/profiles/mit.hpp"
#include "jacobid/hal/profiles/odrive.hpp"
#include "jacobid/span.hpp"

namespace jacobid::hal {

using ProfileConfig = std::variant<mit::JointConfig, cia402::JointConfig, odrive::JointConfig, generic::JointConfig>;

struct DecoderSetConfigResult {
    ConfigStatus status = ConfigStatus::Ok;
    std::size_t joint = 0;  // first offending joint
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
            const ConfigStatus s = configure_one(j, joints[j]);
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

    DecodeStatus dispatch(const CanFrame& f) noexcept {
        ++counters_.frames;
        for (std::size_t j = 0; j < count_; ++j) {
            const DecodeStatus s = decode_one(j, f);
            if (s == DecodeStatus::NotMine) continue;
            if (s == DecodeStatus::Ok) {
                ++counters_.decoded;
                update_stale(states_[j], max_age_);
            } else {
                count_rejection(s);
                states_[j].decode_error = true;
            }
            return s;
        }
        ++counters_.rejected_unknown_id;
        return DecodeStatus::UnknownId;
    }

    // Dispatches every frame; returns how many were decoded.
    std::size_t dispatch(Span<const CanFrame> frames) noexcept {
        std::size_t ok = 0;
        for (const CanFrame& f : frames) ok += dispatch(f) == DecodeStatus::Ok ? 1u : 0u;
        return ok;
    }

    // Forget the unwrapping history (e.g. after a drive re-homed); states are kept until refreshed.
    void reset_unwrapping() noexcept {
        for (std::size_t j = 0; j < count_; ++j) {
            switch (decoders_[j].index()) {
                case 0: std::get_if<0>(&decoders_[j])->reset(); break;
                case 1: std::get_if<1>(&decoders_[j])->reset(); break;
                case 2: std::get_if<2>(&decoders_[j])->reset(); break;
                case 3: std::get_if<3>(&decoders_[j])->reset(); break;
                default: break;
            }
        }
    }

    std::size_t joint_count() const noexcept { return count_; }
    const JointState& state(std::size_t j) const noexcept { return states_[j]; }
    Span<const JointState> states() const noexcept { return {states_.data(), count_}; }
    const DecodeCounters& counters() const noexcept { return counters_; }

private:
    using AnyDecoder = std::variant<mit::JointDecoder, cia402::JointDecoder, odrive::JointDecoder, generic::JointDecoder>;

    ConfigStatus configure_one(std::size_t j, const ProfileConfig& c) noexcept {
        // get_if rather than std::visit on the config: the alternatives are constructed explicitly.
        if (const auto* m = std::get_if<mit::JointConfig>(&c)) return emplace<mit::JointDecoder>(j, *m);
        if (const auto* p = std::get_if<cia402::JointConfig>(&c)) return emplace<cia402::JointDecoder>(j, *p);
        if (const auto* o = std::get_if<odrive::JointConfig>(&c)) return emplace<odrive::JointDecoder>(j, *o);
        if (const auto* g = std::get_if<generic::JointConfig>(&c)) return emplace<generic::JointDecoder>(j, *g);
        return ConfigStatus::InvalidLayout;  // valueless variant
    }
    template <typename Decoder, typename Config>
    ConfigStatus emplace(std::size_t j, const Config& c) noexcept {
        return decoders_[j].template emplace<Decoder>().configure(c);
    }

    DecodeStatus decode_one(std::size_t j, const CanFrame& f) noexcept {
        // A switch on the index keeps std::visit's (never taken) bad_variant_access path out of the cycle.
        JointState& s = states_[j];
        switch (decoders_[j].index()) {
            case 0: return std::get_if<0>(&decoders_[j])->decode(f, s);
            case 1: return std::get_if<1>(&decoders_[j])->decode(f, s);
            case 2: return std::get_if<2>(&decoders_[j])->decode(f, s);
            case 3: return std::get_if<3>(&decoders_[j])->decode(f, s);
            default: return DecodeStatus::NotMine;
        }
    }

    void count_rejection(DecodeStatus s) noexcept {
        switch (s) {
            case DecodeStatus::Short: ++counters_.rejected_short; break;
            case DecodeStatus::OutOfRange: ++counters_.rejected_out_of_range; break;
            case DecodeStatus::UnknownId: ++counters_.rejected_unknown_id; break;
            default: ++counters_.rejected_malformed; break;
        }
    }

    std::array<AnyDecoder, MaxJoints> decoders_{};
    std::array<JointState, MaxJoints> states_{};
    DecodeCounters counters_{};
    std::size_t count_ = 0;
    std::uint32_t max_age_ = 0;
};

}  // namespace jacobid::hal
