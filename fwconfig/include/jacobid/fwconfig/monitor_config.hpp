// SPDX-License-Identifier: MIT
#pragma once
// The contact monitor on the controller (fw.yaml `monitor:`, docs/firmware.md "Contact monitor"; issue 40):
// which files describe it, what a detection does, and the model and thresholds read from those files at
// start-up as plain lib-level data (chain rows, standard parameters in the lib's layout, friction,
// thresholds). The firmware library reads only the section; the files are turned into a MonitorModel by
// the host's own readers (host-tools/src/monitor/firmware_monitor_model.hpp, linked into jacobid-fw), so
// that the controller runs exactly the model `identify --export-robot` wrote and the thresholds
// `jacobid monitor calibrate` wrote, parsed by the code that wrote them.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "jacobid/robot/contact_detector.hpp"
#include "jacobid/robot/joint_friction.hpp"
#include "jacobid/robot/kinematic_chain.hpp"
#include "jacobid/robot/standard_parameters.hpp"

namespace jacobid::firmware {

// What a confirmed contact does in the cycle that confirms it.
enum class MonitorAction {
    Stop,  // the playback's hold through each profile's command path, the drive enable dropped (e-stop line), and the flag
    Flag,  // the stream flag only (commissioning: watch the estimate before it may stop anything)
};

struct MonitorModel {
    std::vector<robot::ChainJoint> chain;                  // the serial chain, base to tip
    Eigen::Vector3d gravity{0.0, 0.0, -9.81};              // m/s^2 in the base frame
    robot::StandardParameterOptions options{};             // the standard parameters' layout
    std::vector<robot::CoulombSign> coulomb;               // per joint
    std::vector<double> standard;                          // standard parameters, the lib layout's order
    std::vector<robot::JointFrictionParameters> friction;  // per joint (presliding, standstill)
    std::vector<robot::JointThresholds> thresholds;        // per joint, N.m
    double gain = 100.0;                                   // 1/s: the momentum observer's K
    int confirm = 1;                                       // consecutive rows in contact before it counts
};

struct MonitorConfig {
    bool enabled = false;
    std::string robot;       // monitor.robot: the description `identify --export-robot` wrote (path)
    std::string thresholds;  // monitor.thresholds: the monitor YAML `jacobid monitor calibrate` wrote (path)
    MonitorAction action = MonitorAction::Stop;
    // monitor.stream: true sends version-2 datagrams (tau_ext, contact flags); false keeps version 1 for
    // receivers built before it, the detection and its action unchanged.
    bool stream = true;
    MonitorModel model;  // filled from the two files before FirmwareCycle::configure
};

const char* to_string(MonitorAction action) noexcept;

}  // namespace jacobid::firmware
