// SPDX-License-Identifier: MIT
#include "excite/parameter_scales.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "robot/serial_robot_model.hpp"

namespace jacobid::excite {
namespace {

constexpr double kGravity = 9.81;
constexpr double kMinLength = 0.05;  // m

// "ZZ1R" -> {"ZZ", 1}; "FOFF12" -> {"FOFF", 12}; no digits: joint 0.
std::pair<std::string, int> kind_and_joint(const std::string& name) {
    std::size_t i = 0;
    while (i < name.size() && std::isalpha(static_cast<unsigned char>(name[i]))) ++i;
    std::size_t k = i;
    while (k < name.size() && std::isdigit(static_cast<unsigned char>(name[k]))) ++k;
    const int joint = k > i ? std::stoi(name.substr(i, k - i)) : 0;
    return {name.substr(0, i), joint};
}

// The description's standard masses M1..Mn (0 where not known) and the mean distance between joint origins.
void masses_and_length(const robot::RobotDescription& d, const robot::RobotModel& model, std::vector<double>& mass, double& length) {
    const int n = model.joint_count();
    mass.assign(static_cast<std::size_t>(n), 0.0);
    length = kMinLength;
    if (const auto* serial = dynamic_cast<const robot::SerialRobotModel*>(&model)) {
        const Eigen::VectorXd standard = robot::standard_values(d, *serial);
        for (int j = 0; j < n; ++j) {
            const int index = serial->standard_index("M" + std::to_string(j + 1));
            if (index >= 0) mass[static_cast<std::size_t>(j)] = std::max(0.0, standard[index]);
        }
        double sum = 0.0;
        int count = 0;
        for (const auto& joint : serial->config().joints) {
            if (joint.position.norm() > 1e-9) sum += joint.position.norm(), ++count;
        }
        if (count > 0) length = std::max(kMinLength, sum / count);
    } else if (d.model == "planar2r") {
        length = std::max(kMinLength, d.L1);
    }
    if (std::all_of(mass.begin(), mass.end(), [](double m) { return m <= 0.0; })) mass.assign(mass.size(), 1.0);
}

}  // namespace

Eigen::VectorXd physical_scales(const robot::RobotDescription& description, const robot::RobotModel& model, const Eigen::VectorXd& prior) {
    const int n = model.joint_count();
    std::vector<double> mass;
    double length = kMinLength;
    masses_and_length(description, model, mass, length);
    std::vector<double> carried(static_cast<std::size_t>(n), 0.0);  // m_j: the mass joint j carries
    for (int j = n - 1; j >= 0; --j) carried[static_cast<std::size_t>(j)] = mass[static_cast<std::size_t>(j)] + (j + 1 < n ? carried[static_cast<std::size_t>(j + 1)] : 0.0);
    const auto& names = model.parameter_names();
    // Per joint, the prior's friction level.
    std::map<int, double> friction;
    for (std::size_t k = 0; k < names.size(); ++k) {
        const auto [kind, joint] = kind_and_joint(names[k]);
        if (kind == "FC" || kind == "FV" || kind == "FOFF") friction[joint] = std::max(friction[joint], std::abs(prior[static_cast<Eigen::Index>(k)]));
    }
    Eigen::VectorXd scale(static_cast<Eigen::Index>(names.size()));
    for (std::size_t k = 0; k < names.size(); ++k) {
        const auto [kind, joint] = kind_and_joint(names[k]);
        const double m = joint >= 1 && joint <= n ? carried[static_cast<std::size_t>(joint - 1)] : carried.front();
        double level = friction.count(joint) ? friction[joint] : 0.0;
        if (!(level > 0.0)) level = 0.01 * m * kGravity * length;
        double p = 1.0;
        if (kind == "XX" || kind == "XY" || kind == "XZ" || kind == "YY" || kind == "YZ" || kind == "ZZ" || kind == "IA") {
            p = m * length * length;
        } else if (kind == "MX" || kind == "MY" || kind == "MZ") {
            p = m * length;
        } else if (kind == "M") {
            p = m;
        } else if (kind == "FC" || kind == "FOFF" || kind == "FV") {
            p = level;
        }
        scale[static_cast<Eigen::Index>(k)] = p;
    }
    return scale;
}

Eigen::VectorXd prior_scales(const robot::RobotDescription& description, const robot::RobotModel& model, const Eigen::VectorXd& prior) {
    return prior.cwiseAbs().cwiseMax(0.1 * physical_scales(description, model, prior));
}

}  // namespace jacobid::excite
