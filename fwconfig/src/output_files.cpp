// SPDX-License-Identifier: MIT
#include "output_files.hpp"

#include <fmt/core.h>

#include <filesystem>
#include <system_error>

#include "jacobid/fwconfig/firmware_config_yaml.hpp"
#include "jacobid/yaml/yaml_section.hpp"

namespace jacobid::firmware {

bool same_file(const std::string& a, const std::string& b) {
    namespace fs = std::filesystem;
    std::error_code error;
    if (fs::exists(a, error) && fs::exists(b, error)) {
        const bool equivalent = fs::equivalent(a, b, error);
        if (!error) return equivalent;
    }
    const fs::path canonical_a = fs::weakly_canonical(a, error);
    if (error) return false;
    const fs::path canonical_b = fs::weakly_canonical(b, error);
    return !error && canonical_a == canonical_b;
}

void require_outputs_apart(const std::string& source, const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
    for (std::size_t o = 0; o < outputs.size(); ++o) {
        const NamedPath& out = outputs[o];
        if (out.path.empty()) continue;
        auto refuse = [&](const NamedPath& other, const char* why) {
            throw ConfigError(fmt::format("{}: {}: '{}' is the same file as {} ('{}'): {}", yaml::where(source, out.node), out.name, out.path,
                                          other.name, other.path, why));
        };
        for (const NamedPath& in : inputs) {
            if (!in.path.empty() && same_file(out.path, in.path)) refuse(in, "writing there would overwrite that input; give another file");
        }
        for (std::size_t e = 0; e < o; ++e) {
            if (!outputs[e].path.empty() && same_file(out.path, outputs[e].path)) refuse(outputs[e], "give each output its own file");
        }
    }
}

}  // namespace jacobid::firmware
