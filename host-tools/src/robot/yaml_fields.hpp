// SPDX-License-Identifier: MIT
#pragma once
// Typed reads of YAML fields with InputError messages "file:line:column: 'key' must be ...", shared by
// the robot description parsers.
#include <yaml-cpp/yaml.h>

#include <set>
#include <string>

namespace jacobid::robot::yaml_fields {

// "file:line:column" of the node, or just the file when the node has no mark.
std::string where(const std::string& source, const YAML::Node& node);
double number(const std::string& source, const YAML::Node& node, const std::string& key);
int integer(const std::string& source, const YAML::Node& node, const std::string& key);
bool boolean(const std::string& source, const YAML::Node& node, const std::string& key);
std::string text(const std::string& source, const YAML::Node& node, const std::string& key);
// InputError naming the first key of `map` not in `known`.
void check_keys(const std::string& source, const YAML::Node& map, const std::set<std::string>& known, const std::string& what);

}  // namespace jacobid::robot::yaml_fields
