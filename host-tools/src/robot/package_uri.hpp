// SPDX-License-Identifier: MIT
#pragma once
// A ROS `package://PACKAGE/PATH` URI (how URDFs of ROS robots name their files) resolved to a file, the way
// ROS finds a package: ROS 1's ROS_PACKAGE_PATH (each entry a package or a folder of packages) and ROS 2's
// AMENT_PREFIX_PATH (each prefix's share/PACKAGE), a package being a folder with a package.xml. Before issue
// 36 such a URI was joined to the description's folder as a path ("dir/package:/arm/urdf/arm.urdf").
#include <string>

namespace jacobid::robot {

bool is_package_uri(const std::string& text);

// The file the URI names, or why it was not found (what was searched, how to fix it).
struct ResolvedPackageUri {
    std::string path;  // empty: not found
    std::string why;   // when not found: what was searched, and how to fix it
};
ResolvedPackageUri resolve_package_uri(const std::string& uri);

}  // namespace jacobid::robot
