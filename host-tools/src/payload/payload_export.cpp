// SPDX-License-Identifier: MIT
#include "payload/payload_export.hpp"

#include <fmt/core.h>

#include <algorithm>

#include "identify/drive_gains/drive_gains.hpp"
#include "robot/urdf_chain.hpp"

namespace jacobid::payload {

std::string last_link_name(const robot::RobotDescription& d) {
    if (d.model == "urdf" && !d.urdf.empty()) {
        const robot::UrdfChain chain = robot::load_urdf_chain(d.urdf);
        if (!chain.body_links.empty()) return chain.body_links.back();
    }
    return fmt::format("link{}", d.joints.size());
}

std::string urdf_fragment(const PayloadEstimate& e, const robot::RobotDescription& description) {
    const Eigen::Vector3d p = e.tool.translation();
    // URDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll).
    const Eigen::Vector3d ypr = e.tool.linear().eulerAngles(2, 1, 0);
    const Inertial& i = e.inertial;
    std::string t;
    const bool prior = e.status[0] == Status::Prior;
    t += fmt::format("<!-- payload estimated by jacobid payload from {}{} (frame: {}); mass std {:.3g} kg{} -->\n", e.loaded_source,
                     e.unloaded_source.empty() ? "" : " and " + e.unloaded_source, e.frame_name, e.std_total[0],
                     prior ? "; inertia: the point-mass prior (the motion did not determine it)" : "");
    t += fmt::format("<joint name=\"payload_joint\" type=\"fixed\">\n  <parent link=\"{}\"/>\n  <child link=\"payload\"/>\n", last_link_name(description));
    t += fmt::format("  <origin xyz=\"{:.9g} {:.9g} {:.9g}\" rpy=\"{:.9g} {:.9g} {:.9g}\"/>\n</joint>\n", p.x(), p.y(), p.z(), ypr[2], ypr[1], ypr[0]);
    t += "<link name=\"payload\">\n  <inertial>\n";
    t += fmt::format("    <origin xyz=\"{:.9g} {:.9g} {:.9g}\" rpy=\"0 0 0\"/>\n    <mass value=\"{:.9g}\"/>\n", i.com.x(), i.com.y(), i.com.z(), i.mass);
    t += fmt::format("    <inertia ixx=\"{:.9g}\" ixy=\"{:.9g}\" ixz=\"{:.9g}\" iyy=\"{:.9g}\" iyz=\"{:.9g}\" izz=\"{:.9g}\"/>\n", i.inertia[0], i.inertia[1],
                     i.inertia[2], i.inertia[3], i.inertia[4], i.inertia[5]);
    t += "  </inertial>\n</link>\n";
    return t;
}

robot::RobotDescription with_payload(const ArmModel& arm, const Standard10& standard) {
    robot::RobotDescription d = arm.description;
    const Eigen::VectorXd values = robot::standard_values(d, *arm.serial);
    const std::vector<int> link = identify::last_link_columns(*arm.serial);
    for (int k = 0; k < 10; ++k) {
        const int index = link[static_cast<std::size_t>(k)];
        const std::string& name = arm.serial->standard_names()[static_cast<std::size_t>(index)];
        const double value = values[index] + standard[k];
        auto it = std::find_if(d.parameters.begin(), d.parameters.end(), [&](const auto& p) { return p.first == name; });
        if (it != d.parameters.end()) it->second = value;
        else d.parameters.emplace_back(name, value);
    }
    return d;
}

}  // namespace jacobid::payload
