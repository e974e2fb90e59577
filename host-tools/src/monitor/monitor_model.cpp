// SPDX-License-Identifier: MIT
#include "monitor/monitor_model.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "robot/presliding_model.hpp"

namespace jacobid::monitor {
namespace {

double parameter_or(const robot::RobotDescription& d, const std::string& name, double fallback) {
    for (const auto& [key, value] : d.parameters) {
        if (key == name) return value;
    }
    return fallback;
}

// The serial chain's own description: without the friction extensions' parameters (FCLj of coulomb_load, FDj of
// presliding), which are no standard parameters of the chain; the monitor reads them from the full description.
robot::RobotDescription chain_description(robot::RobotDescription d) {
    d.coulomb_load = robot::CoulombLoad::none;
    d.presliding = false;
    std::vector<std::pair<std::string, double>> kept;
    for (const auto& p : d.parameters) {
        if (p.first.rfind("FCL", 0) != 0 && p.first.rfind("FD", 0) != 0) kept.push_back(p);
    }
    d.parameters = kept;
    return d;
}

}  // namespace

MonitorModel load_monitor_model(const std::string& path, const std::vector<double>& standing_velocity, double standing_time, double sample_period,
                                const std::vector<double>& band_margin) {
    MonitorModel m;
    m.description = robot::load_robot_description(path);
    const robot::RobotDescription& d = m.description;
    const robot::RobotDescription chain = chain_description(d);
    if (d.model != "mdh" && d.model != "urdf") {
        throw InputError(fmt::format("{}: model '{}': the monitor needs a serial robot (model mdh or urdf)", path, d.model));
    }
    const auto model = robot::make_robot_model(chain);
    const auto* serial = dynamic_cast<const robot::SerialRobotModel*>(&robot::rigid_body(*model));
    if (!serial) throw InputError(fmt::format("{}: not a serial robot model", path));
    const int n = serial->joint_count();
    if (!standing_velocity.empty() && standing_velocity.size() != 1 && static_cast<int>(standing_velocity.size()) != n) {
        throw InputError(fmt::format("--standing-velocity: {} values for {} joints (expected 1 or {})", standing_velocity.size(), n, n));
    }
    if (!band_margin.empty() && band_margin.size() != 1 && static_cast<int>(band_margin.size()) != n) {
        throw InputError(fmt::format("--band-margin: {} values for {} joints (expected 1 or {})", band_margin.size(), n, n));
    }
    const auto regressor = robot::make_rnea_regressor<kJoints>(serial->config());
    const Eigen::VectorXd standard = robot::standard_values(chain, *serial);
    robot::RneaRegressor<kJoints>::Parameters X = robot::RneaRegressor<kJoints>::Parameters::Zero();
    // The host's standard order is the lib layout's (serial_robot_model.hpp builds one from the other).
    if (standard.size() != regressor.parameter_count()) throw std::logic_error("monitor: standard parameter count differs from the lib layout");
    X.head(standard.size()) = standard;
    m.config = serial->config();
    m.standard = standard;
    m.terms = std::make_unique<robot::RigidBodyTerms<kJoints>>(regressor, X);
    m.friction = robot::JointFriction<kJoints>(regressor, X);
    const robot::PreslidingSettings presliding = robot::presliding_settings(d);
    for (int j = 0; j < n; ++j) {
        robot::JointFrictionParameters p = m.friction.joint(j);
        if (d.presliding) {
            p.presliding = parameter_or(d, fmt::format("FD{}", j + 1), 0.0);
            p.presliding_displacement = presliding.displacement[static_cast<std::size_t>(j)];
            p.presliding_play = presliding.play_width;
        }
        // FCLj of coulomb_load: its reference gravity is the description's own parameters (with_load_friction),
        // i.e. the model's g(q) the observer computes anyway.
        if (d.coulomb_load != robot::CoulombLoad::none) {
            p.load = parameter_or(d, fmt::format("FCL{}", j + 1), 0.0);
            p.load_square = d.coulomb_load == robot::CoulombLoad::square;
        }
        if (!standing_velocity.empty()) p.standing_velocity = standing_velocity[standing_velocity.size() == 1 ? 0 : static_cast<std::size_t>(j)];
        p.standing_samples = std::max(1, static_cast<int>(std::lround(standing_time / sample_period)));
        if (!(p.standing_velocity >= 0.0)) throw InputError(fmt::format("--standing-velocity: {} rad/s must be >= 0", p.standing_velocity));
        if (!band_margin.empty()) p.band_margin = band_margin[band_margin.size() == 1 ? 0 : static_cast<std::size_t>(j)];
        if (!(p.band_margin >= 0.0)) throw InputError(fmt::format("--band-margin: {} must be >= 0", p.band_margin));
        m.friction.set_joint(j, p);
    }
    return m;
}

}  // namespace jacobid::monitor
