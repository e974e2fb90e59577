// SPDX-License-Identifier: MIT
#include "diagnose/robot_export.hpp"

#include <fmt/core.h>

#include <filesystem>

namespace jacobid::diagnose {
namespace {

namespace fs = std::filesystem;

// A named effect as the description's own option; false (and `why`) when the description has none.
bool add_effect(robot::RobotDescription& d, const EffectEstimate& e, std::string& option, std::string& why) {
    const sim::EffectTerm& t = e.term;
    switch (t.kind) {
        case sim::EffectKind::CoulombOffset:
            d.friction_offset = true;
            option = "friction: offset: true";
            return true;
        case sim::EffectKind::RotorInertia:
            d.rotor_inertia = true;
            option = "rotor_inertia: true";
            return true;
        case sim::EffectKind::Presliding:
            d.presliding = true;
            // A fixed list keeps its other joints and takes the named x_p; auto lets identify choose per joint on
            // held-out data over the grid the candidate searched.
            if (!d.presliding_displacement_auto) {
                if (d.presliding_displacements.empty()) d.presliding_displacements.assign(d.joints.size(), d.presliding_displacement);
                d.presliding_displacements[static_cast<std::size_t>(t.joint)] = t.displacement;
            }
            option = d.presliding_displacement_auto ? "friction: presliding: dahl (presliding_displacement: auto)"
                                                    : fmt::format("friction: presliding: dahl, presliding_displacement {:g} rad on joint {}", t.displacement, t.joint + 1);
            return true;
        case sim::EffectKind::CoulombLoad:
            d.coulomb_load = robot::CoulombLoad::abs;
            option = "friction: coulomb_load: abs";
            return true;
        case sim::EffectKind::CoulombSmoothing:
            if (d.coulomb_alpha_auto) {
                option = "friction: alpha: auto (kept: identify chooses each joint's smoothing on held-out data)";
            } else {
                if (d.coulomb_alpha.empty()) d.coulomb_alpha.assign(d.joints.size(), d.coulomb.alpha);
                d.coulomb_alpha[static_cast<std::size_t>(t.joint)] = t.alpha;
                option = fmt::format("friction: alpha {:g} s/rad on joint {}", t.alpha, t.joint + 1);
            }
            return true;
        case sim::EffectKind::TorqueDelay:
            why = fmt::format("a delay is not part of the description: identify --torque-delay {:g} (or auto)", e.value);
            return false;
        default:
            why = "identify's model has no such term";
            return false;
    }
}

// The URDF as the exported file will name it: relative to the file's folder (load_robot_description resolves it so).
std::string urdf_relative_to(const std::string& urdf, const std::string& path) {
    const fs::path absolute = fs::absolute(urdf).lexically_normal();
    const fs::path relative = absolute.lexically_relative(fs::absolute(path).lexically_normal().parent_path());
    return relative.empty() ? absolute.string() : relative.string();
}

}  // namespace

ExportedDescription export_diagnosed_robot(const robot::RobotDescription& description, const Diagnosis& diagnosis, const std::string& path) {
    ExportedDescription out;
    out.description = description;
    robot::RobotDescription& d = out.description;
    for (const EffectEstimate& e : diagnosis.effects) {
        std::string option, why;
        const std::string label = e.test.label();
        if (add_effect(d, e, option, why)) out.added.push_back(fmt::format("{}: {}", label, option));
        else out.not_in_description.push_back(fmt::format("{}: {}", label, why));
    }
    if (d.model == "urdf") d.urdf = urdf_relative_to(d.urdf, path);
    std::string header = fmt::format("# jacobid diagnose on {}: {} with the effects it named as model options", diagnosis.log_source, description.source);
    for (const std::string& a : out.added) header += "\n#   added: " + a;
    for (const std::string& n : out.not_in_description) header += "\n#   not in the description: " + n;
    out.yaml = header + "\n" + robot::to_yaml(d);
    out.summary = {{"robot", path}, {"added", out.added}, {"not_in_description", out.not_in_description}};
    return out;
}

}  // namespace jacobid::diagnose
