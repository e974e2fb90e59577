// SPDX-License-Identifier: MIT
#pragma once
// fw.yaml `monitor:` for the firmware tests: the chain's 2R robot as an MDH description carrying the
// simulator's true (Table II) parameters, as if identified exactly, and a monitor YAML with the thresholds
// given, read by jacobid-fw's own loader (host-tools/src/monitor/firmware_monitor_model.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <string>

#include "firmware_test_support.hpp"
#include "monitor/firmware_monitor_model.hpp"
#include "scratch_directory.hpp"

namespace jacobid::test {

// The paper's 2R (examples/robots/planar2r_mdh.yaml): ZZ1R = ZZ1 + 0.25 M2 = 3.496 as in Table II.
inline std::string planar2r_mdh_yaml() {
    return "model: mdh\ngravity: [0, 0, -9.81]\njoints:\n"
           "  - {name: j1, sigma: 0, alpha: 0, d: 0,   theta: 0, r: 0}\n"
           "  - {name: j2, sigma: 0, alpha: 0, d: 0.5, theta: 0, r: 0}\n"
           "friction: {coulomb: smooth, alpha: 100}\n"
           "parameters: {ZZ1: 2.996, M2: 2.0, FV1: 0.248, FC1: 0.431, ZZ2: 0.059, MX2: 0.124, MY2: 0.0019, FV2: 0.0144, FC2: 0.1268}\n";
}

// Per joint, N.m: moving, and beyond the Coulomb band standing; the band margin (monitor YAML band_margin).
struct Thresholds {
    std::array<double, 2> moving{3.0, 1.0}, standing{1.0, 0.5};
    double band_margin = 0.0;
};

// The observer's gain 100/s; the windows of chain_config()'s estimator.
inline std::string monitor_yaml(const Thresholds& t) {
    std::string s = "estimator: {type: observer, gain: 100, velocity_window: 0.05, xi: 0}\n"
                    "standing_velocity: 0.02\nstanding_time: 0.1\nconfirm: 1\nband_margin: " + std::to_string(t.band_margin) + "\njoints:\n";
    for (std::size_t j = 0; j < 2; ++j) s += "  - {moving: " + std::to_string(t.moving[j]) + ", standing: " + std::to_string(t.standing[j]) + "}\n";
    return s;
}

// chain_config(extra) with a `monitor:` section (action `action`) whose files are written into the scratch
// directory under `tag`, loaded as jacobid-fw loads them.
inline firmware::FirmwareConfig monitored_chain_config(const std::string& tag, const std::string& action, const std::string& extra = "",
                                                       const Thresholds& thresholds = {}) {
    const std::string dir = scratch_directory().string() + "/";
    std::ofstream(dir + tag + "_robot.yaml") << planar2r_mdh_yaml();
    std::ofstream(dir + tag + "_monitor.yaml") << monitor_yaml(thresholds);
    firmware::FirmwareConfig c = firmware::parse_firmware_config(
        chain_config_yaml(extra) + "monitor: {robot: " + tag + "_robot.yaml, thresholds: " + tag + "_monitor.yaml, action: " + action + "}\n",
        dir + "fw.yaml");
    c.monitor.model = monitor::load_firmware_monitor(c).model;
    return c;
}

// The calibration `jacobid monitor calibrate --false-alarm-rate 0` makes, on the firmware's own estimates:
// per joint the largest |tau_ext| while moving and the largest excess over the Coulomb band while standing,
// times (1 + margin). Fed by every row of contact-free runs.
struct ThresholdCalibration {
    Thresholds seen{{0.0, 0.0}, {0.0, 0.0}};
    void add(const firmware::CycleMonitor& m) {
        if (!m.last().started) return;
        const auto& e = m.estimate();
        for (std::size_t j = 0; j < 2; ++j) {
            const auto i = static_cast<Eigen::Index>(j);
            const double r = std::abs(e.external[i]);
            if (e.standing[j]) seen.standing[j] = std::max(seen.standing[j], r - e.band[i]);
            else seen.moving[j] = std::max(seen.moving[j], r);
        }
    }
    Thresholds thresholds(double margin) const {
        Thresholds t;
        for (std::size_t j = 0; j < 2; ++j) {
            t.moving[j] = (1.0 + margin) * seen.moving[j];
            t.standing[j] = (1.0 + margin) * std::max(seen.standing[j], 0.0);
        }
        return t;
    }
};

}  // namespace jacobid::test
