// SPDX-License-Identifier: MIT
#pragma once
// The one list of device profiles. Everything that handles "any profile" goes through it: the decoder
// set (JointDecoderSet), the firmware's YAML reader (names, defaults, keys), sim-can's drive side
// (telemetry) and the trajectory playback (commands). Adding a profile is its header plus one line in
// `Profiles` below (walkthrough: docs/profiles.md).
//
// What a profile header defines: profiles/profile_entry.hpp.
// Dispatch is a compile-time index recursion with std::get_if: no std::visit (its bad_variant_access
// path), no virtual calls, nothing allocated; the cycle stays exception- and heap-free.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>

#include "jacobid/hal/can_frame.hpp"
#include "jacobid/hal/joint_command.hpp"
#include "jacobid/hal/joint_state.hpp"
#include "jacobid/hal/profiles/cia402.hpp"
#include "jacobid/hal/profiles/generic.hpp"
#include "jacobid/hal/profiles/mit.hpp"
#include "jacobid/hal/profiles/odrive.hpp"

namespace jacobid::hal {

template <typename... P>
struct ProfileList {
    using Config = std::variant<typename P::Config...>;
    using Decoder = std::variant<typename P::Decoder...>;
    template <std::size_t I>
    using At = std::tuple_element_t<I, std::tuple<P...>>;
    static constexpr std::size_t kCount = sizeof...(P);
    static constexpr std::size_t kMaxTelemetryFrames = std::max({P::kTelemetryFrames...});
};

// The registry: one line per profile. The order is the fw.yaml order of names (mit, cia402, odrive).
using Profiles = ProfileList<
    mit::Profile,
    cia402::Profile,
    odrive::Profile,
    generic::Profile>;

using ProfileConfig = Profiles::Config;   // one joint's configuration, any profile
using AnyJointDecoder = Profiles::Decoder;
constexpr std::size_t kMaxTelemetryFrames = Profiles::kMaxTelemetryFrames;
constexpr std::size_t kMaxCommandFrames = 3;  // generic: one frame per setpoint signal at most

// A profile as a value, to pass it to a generic lambda: [](auto tag) { using P = typename decltype(tag)::type; }
template <typename P>
struct ProfileTag {
    using type = P;
};

// Calls f(ProfileTag<P>{}, alternative) for the profile P a variant (of configs or decoders) holds;
// `valueless` when it holds none.
template <typename R, std::size_t I = 0, typename Variant, typename F>
R visit_profile(Variant& v, F&& f, R valueless) noexcept {
    if constexpr (I == Profiles::kCount) {
        return valueless;
    } else {
        if (auto* alternative = std::get_if<I>(&v)) return f(ProfileTag<typename Profiles::template At<I>>{}, *alternative);
        return visit_profile<R, I + 1>(v, std::forward<F>(f), valueless);
    }
}

// Calls f(ProfileTag<P>{}) for every profile, in registry order.
template <std::size_t I = 0, typename F>
void for_each_profile(F&& f) {
    if constexpr (I < Profiles::kCount) {
        f(ProfileTag<typename Profiles::template At<I>>{});
        for_each_profile<I + 1>(std::forward<F>(f));
    }
}

// Calls f(ProfileTag<P>{}) for the profile named `name`; false when no profile has that name.
template <std::size_t I = 0, typename F>
bool with_profile_named(const char* name, F&& f) {
    if constexpr (I == Profiles::kCount) {
        return false;
    } else {
        using P = typename Profiles::template At<I>;
        if (std::strcmp(P::kName, name) == 0) {
            f(ProfileTag<P>{});
            return true;
        }
        return with_profile_named<I + 1>(name, std::forward<F>(f));
    }
}

inline const char* profile_name(const ProfileConfig& c) noexcept {
    return visit_profile<const char*>(c, [](auto tag, const auto&) { return decltype(tag)::type::kName; }, "unknown");
}

inline ConfigStatus validate(const ProfileConfig& c) noexcept {
    return visit_profile<ConfigStatus>(c, [](auto, const auto& config) { return validate(config); }, ConfigStatus::InvalidLayout);
}

// Makes `d` the decoder of c's profile and configures it.
inline ConfigStatus configure(AnyJointDecoder& d, const ProfileConfig& c) noexcept {
    return visit_profile<ConfigStatus>(
        c,
        [&d](auto tag, const auto& config) {
            using P = typename decltype(tag)::type;
            return d.template emplace<typename P::Decoder>().configure(config);
        },
        ConfigStatus::InvalidLayout);
}

// The decoder's own test decides whether the frame is its joint's (NotMine otherwise).
inline DecodeStatus decode(AnyJointDecoder& d, const CanFrame& f, JointState& s) noexcept {
    return visit_profile<DecodeStatus>(d, [&](auto, auto& decoder) { return decoder.decode(f, s); }, DecodeStatus::NotMine);
}

inline void reset_unwrapping(AnyJointDecoder& d) noexcept {
    visit_profile<int>(d, [](auto, auto& decoder) { decoder.reset(); return 0; }, 0);
}

// Drive side: the frames of one sample (link-side q, qd, tau) into out[0..kMaxTelemetryFrames); returns how many.
inline std::size_t encode_telemetry(const ProfileConfig& c, double q, double qd, double tau, CanFrame* out) noexcept {
    return visit_profile<std::size_t>(
        c, [&](auto, const auto& config) { return encode_telemetry(config, q, qd, tau, out); }, 0);
}

// Controller side: the command frames of one cycle into out[0..kMaxCommandFrames); returns how many.
inline std::size_t encode_command(const ProfileConfig& c, const JointCommand& cmd, CanFrame* out) noexcept {
    return visit_profile<std::size_t>(c, [&](auto, const auto& config) { return encode_command(config, cmd, out); }, 0);
}

// Drive side: a command frame as the joint's device reads it (link side). NotMine when it is not the
// joint's; `drive_mode` is the device's own mode where the frame does not say (CiA 402: 0x6060).
inline DecodeStatus decode_command(const ProfileConfig& c, CommandMode drive_mode, const CanFrame& f, JointCommand& out) noexcept {
    return visit_profile<DecodeStatus>(c, [&](auto, const auto& config) { return decode_command(config, drive_mode, f, out); }, DecodeStatus::NotMine);
}

}  // namespace jacobid::hal
