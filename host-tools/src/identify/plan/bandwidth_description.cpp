// SPDX-License-Identifier: MIT
#include "identify/plan/bandwidth_description.hpp"

#include <fmt/core.h>

namespace jacobid::identify {
namespace {

// The torques' part of the description: what each torque's floor held, which were left out.
std::string describe_torque(const TorqueBandwidth& t) {
    std::string s, floors, unused;
    for (const auto& j : t.joints) {
        if (!j.moving) continue;
        if (j.used) {
            floors += fmt::format("{}{} {:.2g} % (noise {:.2g} rms)", floors.empty() ? "" : ", ", j.name, 100.0 * j.floor_fraction, j.noise_rms);
        } else {
            unused += (unused.empty() ? "" : ", ") + j.name;
        }
    }
    if (!floors.empty()) s += fmt::format("; torque floor share{}: {}", t.noise_known ? " (noise given)" : "", floors);
    if (!unused.empty()) s += "; torques not used (within 10 x noise RMS): " + unused;
    if (!(t.frequency > 0.0)) s += "; no torque rises 10 x above its noise floor: the velocity's band alone";
    return s;
}

}  // namespace

std::string moving_joint_names(const std::vector<JointBandwidth>& joints, bool used) {
    std::string s;
    for (const auto& j : joints) {
        if (j.used != used || !j.moving) continue;
        s += (s.empty() ? "" : ", ") + j.name;
    }
    return s;
}

std::string describe_bandwidth(const BandwidthEstimate& e, double ratio) {
    std::string s;
    if (e.noise_limited) {
        s = fmt::format("{:.3g} Hz, limited by the position noise (its share of the acceleration below the {:.3g} Hz differentiator "
                        "cutoff kept under {:.2g}); 99 % of the velocity energy lies below {:.3g} Hz",
                        e.frequency, ratio * e.frequency, kAccelerationNoiseShare, e.energy_frequency);
    } else {
        s = fmt::format("{:.3g} Hz: 99 % of the velocity energy lies below it", e.frequency);
    }
    if (e.torque.estimated() && e.torque.frequency > 0.0) {
        const std::string torque = fmt::format("99 % of the torque's energy above its noise floor lies below {:.3g} Hz (the widest joint's)", e.torque.frequency);
        if (e.torque_noise_limited) {
            s += fmt::format("; {}, but the position noise holds the differentiators and the torque's smoothing at {:.3g} Hz (10 x {:.3g} Hz)", torque,
                             ratio * e.differentiator_frequency, e.differentiator_frequency);
        } else if (e.torque_wider) {
            s += fmt::format("; {}: the differentiators and the torque's smoothing at {:.3g} Hz (10 x {:.3g} Hz)", torque, ratio * e.differentiator_frequency,
                             e.differentiator_frequency);
        } else {
            s += fmt::format("; {}", torque);
        }
    }
    s += fmt::format(" (noise floor removed; joints used: {}", moving_joint_names(e.joints, true));
    if (e.all_below_floor) s += ", all below their noise floor";
    s += ")";
    std::string floors;
    for (const auto& j : e.joints) {
        if (!j.moving) continue;
        floors += fmt::format("{}{} {:.2g} % (noise {:.2g} rad rms{})", floors.empty() ? "" : ", ", j.name, 100.0 * j.floor_fraction,
                              j.noise_rms, j.quantization_step > 0.0 ? fmt::format(", steps of {:.3g} rad", j.quantization_step) : "");
    }
    if (!floors.empty()) s += "; floor share: " + floors;
    const std::string unused = moving_joint_names(e.joints, false);
    if (!unused.empty()) s += "; not used (motion within 10 x noise RMS): " + unused;
    if (e.jumps > 0) {
        std::string where;
        for (const auto& j : e.joints) {
            if (j.jumps > 0) where += fmt::format("{}{} {}", where.empty() ? "" : ", ", j.name, j.jumps);
        }
        s += fmt::format("; {} isolated jump(s) ignored ({})", e.jumps, where);
    }
    if (e.torque.estimated()) s += describe_torque(e.torque);
    return s;
}


}  // namespace jacobid::identify
