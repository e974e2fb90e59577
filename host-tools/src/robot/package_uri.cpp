// SPDX-License-Identifier: MIT
#include "robot/package_uri.hpp"

#include <fmt/core.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <vector>

namespace jacobid::robot {
namespace {

namespace fs = std::filesystem;

constexpr const char* kScheme = "package://";

std::vector<std::string> path_list(const char* variable) {
    std::vector<std::string> entries;
    const char* value = std::getenv(variable);
    std::istringstream in(value ? value : "");
    for (std::string entry; std::getline(in, entry, ':');) {
        if (!entry.empty()) entries.push_back(entry);
    }
    return entries;
}

bool is_package(const fs::path& folder) {
    std::error_code ec;
    return fs::is_regular_file(folder / "package.xml", ec);
}

}  // namespace

bool is_package_uri(const std::string& text) { return text.rfind(kScheme, 0) == 0; }

ResolvedPackageUri resolve_package_uri(const std::string& uri) {
    const std::string rest = uri.substr(std::string(kScheme).size());
    const auto slash = rest.find('/');
    const std::string package = rest.substr(0, slash), inside = slash == std::string::npos ? std::string() : rest.substr(slash + 1);
    if (package.empty() || inside.empty()) return {"", "expected package://PACKAGE/PATH (a file inside a ROS package)"};
    std::vector<fs::path> candidates;
    for (const std::string& entry : path_list("ROS_PACKAGE_PATH")) {
        const fs::path e(entry);
        if (e.filename() == package) candidates.push_back(e);  // the entry is the package itself
        candidates.push_back(e / package);
    }
    for (const std::string& prefix : path_list("AMENT_PREFIX_PATH")) candidates.push_back(fs::path(prefix) / "share" / package);
    for (const fs::path& folder : candidates) {
        std::error_code ec;
        if (is_package(folder) && fs::is_regular_file(folder / inside, ec)) return {(folder / inside).lexically_normal().string(), ""};
    }
    const auto searched = [](const char* variable) {
        const char* value = std::getenv(variable);
        return value && *value ? fmt::format("{}={}", variable, value) : fmt::format("{} unset", variable);
    };
    return {"", fmt::format("no ROS package '{}' holding '{}' ({}, {}: searched ENTRY/{}, ENTRY/share/{} with a package.xml); source the ROS "
                            "workspace that has it, or give the URDF's path (relative to this file or absolute)",
                            package, inside, searched("ROS_PACKAGE_PATH"), searched("AMENT_PREFIX_PATH"), package, package)};
}

}  // namespace jacobid::robot
