// SPDX-License-Identifier: MIT
#include "monitor/firmware_monitor_model.hpp"

#include <fmt/core.h>

#include <cmath>

#include "core/errors.hpp"
#include "monitor/monitor_file.hpp"
#include "monitor/monitor_model.hpp"

namespace jacobid::monitor {

FirmwareMonitorLoad load_firmware_monitor(const firmware::FirmwareConfig& config) {
    const firmware::MonitorConfig& mc = config.monitor;
    const std::size_t joints = config.joints.size();
    const MonitorFile file = load_monitor_file(mc.thresholds, joints);
    if (file.estimator.estimator != Estimator::Observer) {
        throw InputError(fmt::format("{}: estimator.type: {}: the controller runs the momentum observer; calibrate with --estimator observer",
                                     mc.thresholds, to_string(file.estimator.estimator)));
    }
    const MonitorModel m = load_monitor_model(mc.robot, file.standing_velocity, file.standing_time, config.sample_period(), file.band_margin);
    if (static_cast<std::size_t>(m.joints()) != joints) {
        throw InputError(fmt::format("{}: {} joints, but {} has {} (monitor.robot must describe fw.yaml's joints, in their order)", mc.robot,
                                     m.joints(), config.source, joints));
    }
    FirmwareMonitorLoad out;
    firmware::MonitorModel& f = out.model;
    f.chain = m.config.joints;
    f.gravity = m.config.gravity;
    f.options = m.config.options;
    f.standard.assign(m.standard.data(), m.standard.data() + m.standard.size());
    for (std::size_t j = 0; j < joints; ++j) {
        const int ji = static_cast<int>(j);
        f.coulomb.push_back(m.terms->regressor().coulomb(ji));
        f.friction.push_back(m.friction.joint(ji));
    }
    f.thresholds = file.thresholds;
    f.gain = file.estimator.gain;
    f.confirm = file.confirm;
    out.notes = m.notes;
    // The controller's observer sees the bank of fw.yaml `estimator:`; thresholds calibrated through other
    // differentiators saw other noise (docs/firmware.md, "Contact monitor", calibration).
    const firmware::EstimatorConfig& e = config.estimator;
    if (std::abs(file.estimator.velocity_window - e.velocity_window) > 1e-12 || std::abs(file.estimator.xi - e.xi) > 1e-12) {
        out.notes.push_back(fmt::format("{}: calibrated with velocity_window {:g} s, xi {:g}; fw.yaml's estimator has {:g} s, {:g}: the thresholds "
                                        "saw other velocity noise", mc.thresholds, file.estimator.velocity_window, file.estimator.xi,
                                        e.velocity_window, e.xi));
    }
    return out;
}

}  // namespace jacobid::monitor
