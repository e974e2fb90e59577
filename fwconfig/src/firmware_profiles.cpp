// SPDX-License-Identifier: MIT
// The firmware's view of the profile registry (hal/profile_registry.hpp): which profiles fw.yaml offers
// and their defaults. Nothing here names a profile: adding one is its header and one registry line.
#include <string>
#include <vector>

#include "jacobid/fwconfig/firmware_config.hpp"
#include "jacobid/hal/profile_registry.hpp"

namespace jacobid::firmware {

std::vector<std::string> firmware_profile_names() {
    std::vector<std::string> names;
    hal::for_each_profile([&names](auto tag) {
        if constexpr (decltype(tag)::type::kInFirmwareConfig) names.emplace_back(decltype(tag)::type::kName);
    });
    return names;
}

bool default_profile_config(const std::string& profile, std::size_t index, hal::ProfileConfig& out) {
    bool offered = false;
    hal::with_profile_named(profile.c_str(), [&](auto tag) {
        using P = typename decltype(tag)::type;
        if constexpr (P::kInFirmwareConfig) {
            typename P::Config c;
            apply_firmware_defaults(c, index);
            out = c;
            offered = true;
        }
    });
    return offered;
}

}  // namespace jacobid::firmware
