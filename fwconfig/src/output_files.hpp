// SPDX-License-Identifier: MIT
#pragma once
// jacobid-fw's outputs (stream.log, trajectory.log) never overwrite one of its inputs (this fw.yaml, the
// trajectory table) nor each other (issue 36). Checked when fw.yaml is read, before anything is opened for
// writing (FilePublisher::open truncates). Paths are compared as files (std::filesystem::equivalent), so a
// symlink or a hard link to the config is the config. The host tools have their own helper
// (host-tools/src/core/same_file.hpp); firmware/ must not include host-tools headers.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace jacobid::firmware {

// Whether two paths name one file: std::filesystem::equivalent when both exist, else their weakly
// canonical forms (an output not created yet).
bool same_file(const std::string& a, const std::string& b);

struct NamedPath {
    std::string name;  // "stream.log", "trajectory.file", "the configuration file"
    std::string path;
    YAML::Node node;   // where fw.yaml states it (null for the configuration file itself)
};

// Throws ConfigError "fw.yaml:L:C: stream.log: '<path>' is <input>: ..." for the first output that is an
// input or an earlier output. Empty paths (an output not configured) are skipped.
void require_outputs_apart(const std::string& source, const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

}  // namespace jacobid::firmware
