// SPDX-License-Identifier: MIT
#include "robot/yaml_fields.hpp"

#include <fmt/core.h>

#include <cmath>

#include "core/errors.hpp"

namespace jacobid::robot::yaml_fields {

std::string where(const std::string& source, const YAML::Node& node) {
    const YAML::Mark m = node.Mark();
    if (m.is_null()) return source;
    return fmt::format("{}:{}:{}", source, m.line + 1, m.column + 1);
}

double number(const std::string& source, const YAML::Node& node, const std::string& key) {
    try {
        const double v = node.as<double>();
        if (!std::isfinite(v)) throw YAML::Exception(node.Mark(), "not finite");
        return v;
    } catch (const YAML::Exception&) {
        throw InputError(fmt::format("{}: '{}' must be a finite number", where(source, node), key));
    }
}

int integer(const std::string& source, const YAML::Node& node, const std::string& key) {
    try {
        return node.as<int>();
    } catch (const YAML::Exception&) {
        throw InputError(fmt::format("{}: '{}' must be an integer", where(source, node), key));
    }
}

bool boolean(const std::string& source, const YAML::Node& node, const std::string& key) {
    try {
        return node.as<bool>();
    } catch (const YAML::Exception&) {
        throw InputError(fmt::format("{}: '{}' must be true or false", where(source, node), key));
    }
}

std::string text(const std::string& source, const YAML::Node& node, const std::string& key) {
    if (!node.IsScalar()) throw InputError(fmt::format("{}: '{}' must be a string", where(source, node), key));
    return node.as<std::string>();
}

void check_keys(const std::string& source, const YAML::Node& map, const std::set<std::string>& known, const std::string& what) {
    // yaml-cpp keeps both entries of a repeated key and a lookup returns the first: "r: 1, r: 2" would
    // silently mean r = 1. A repeated key is an error (found by fuzz_robot_description).
    std::set<std::string> seen;
    for (const auto& entry : map) {
        if (entry.first.IsScalar() && !seen.insert(entry.first.Scalar()).second) {
            throw InputError(fmt::format("{}: key '{}' appears twice in {}", where(source, entry.first), entry.first.Scalar(), what));
        }
    }
    for (const auto& entry : map) {
        if (!entry.first.IsScalar()) {
            throw InputError(fmt::format("{}: expected a key name in {}, found a list or map used as a key", where(source, entry.first), what));
        }
        const std::string key = entry.first.Scalar();
        if (!known.count(key)) {
            std::string list;
            for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
            throw InputError(fmt::format("{}: unknown key '{}' in {} (known: {})", where(source, entry.first), key, what, list));
        }
    }
}

}  // namespace jacobid::robot::yaml_fields
