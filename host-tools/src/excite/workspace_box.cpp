// SPDX-License-Identifier: MIT
#include "excite/workspace_box.hpp"

#include <fmt/core.h>

#include <cmath>
#include <cstdlib>

#include "core/errors.hpp"
#include "robot/urdf_chain.hpp"

namespace jacobid::excite {
namespace {

constexpr const char* kAxes = "xyz";

// The frame --workspace-frame names: the joint whose frame carries it and the offset from that joint frame.
struct NamedFrame {
    int joint = 0;
    FramePose offset;
};

NamedFrame named_frame(const robot::RobotDescription& robot, const std::string& name) {
    const int n = static_cast<int>(robot.chain.size());
    if (name == "tool" || name == "last") return {n - 1, {}};
    char* end = nullptr;
    const long number = std::strtol(name.c_str(), &end, 10);
    if (!name.empty() && end == name.c_str() + name.size()) {
        if (number < 1 || number > n) throw InputError(fmt::format("--workspace-frame {}: expected a joint number 1 .. {}, tool or last", name, n));
        return {static_cast<int>(number) - 1, {}};
    }
    if (robot.model != "urdf") {
        throw InputError(fmt::format("--workspace-frame {}: expected a joint number 1 .. {}, tool or last (link names need a URDF robot)", name, n));
    }
    const robot::UrdfChain urdf = robot::load_urdf_chain(robot.urdf);
    for (const robot::UrdfLinkFrame& link : urdf.links) {
        if (link.name != name) continue;
        if (link.body < 0) throw InputError(fmt::format("--workspace-frame {}: the link is fixed to the base of {} (expected a link that moves)", name, robot.urdf));
        return {link.body, {link.rotation, link.position}};
    }
    throw InputError(fmt::format("--workspace-frame {}: no such link in {} (expected a link name, a joint number 1 .. {}, tool or last)", name, robot.urdf, n));
}

}  // namespace

const char* face_name(int face) {
    static const char* kNames[kBoxFaces] = {"x max", "x min", "y max", "y min", "z max", "z min"};
    return kNames[face];
}

double face_room(const WorkspaceBox& box, const Eigen::Vector3d& start, int face) {
    const int axis = face / 2;
    return face % 2 == 0 ? box.upper[axis] - start[axis] : start[axis] - box.lower[axis];
}

WorkspaceBox shrink_toward(const WorkspaceBox& box, const Eigen::Vector3d& start, const std::array<double, kBoxFaces>& factors) {
    WorkspaceBox out;
    for (int axis = 0; axis < 3; ++axis) {
        out.upper[axis] = start[axis] + face_room(box, start, 2 * axis) * factors[static_cast<std::size_t>(2 * axis)];
        out.lower[axis] = start[axis] - face_room(box, start, 2 * axis + 1) * factors[static_cast<std::size_t>(2 * axis + 1)];
    }
    return out;
}

WorkspaceCheck check_workspace(const Workspace& workspace, const FourierTrajectory& trajectory, double rate) {
    const int n = trajectory.joints();
    const auto count = static_cast<std::size_t>(std::llround(trajectory.basis.period() * rate));
    WorkspaceCheck r;
    r.min = r.max = workspace.start;
    Eigen::VectorXd q(n), qd(n), qdd(n);
    for (std::size_t i = 0; i <= count; ++i) {
        trajectory.evaluate(static_cast<double>(i) / rate, q, qd, qdd);
        const Eigen::Vector3d p = workspace.frame.point(q, nullptr);
        r.min = r.min.cwiseMin(p), r.max = r.max.cwiseMax(p);
        for (int f = 0; f < kBoxFaces; ++f) {
            const int axis = f / 2;
            const double excursion = f % 2 == 0 ? p[axis] - workspace.start[axis] : workspace.start[axis] - p[axis];
            const double ratio = excursion / face_room(workspace.box, workspace.start, f);
            auto& kept = r.ratio[static_cast<std::size_t>(f)];
            kept = std::max(kept, ratio);
            if (ratio > r.worst) r.worst = ratio, r.worst_face = f, r.worst_sample = i;
        }
    }
    return r;
}

Workspace make_workspace(const robot::RobotDescription& robot, const std::string& frame, const std::vector<double>& point,
                         const std::vector<double>& box, const Eigen::VectorXd& pose) {
    if (robot.chain.empty()) throw InputError(fmt::format("--workspace-frame: needs a serial robot (model mdh or urdf), {} is model {}", robot.source, robot.model));
    if (point.size() != 3) throw InputError(fmt::format("--workspace-point: {} values (expected x,y,z in the frame, m)", point.size()));
    if (box.size() != 6) throw InputError(fmt::format("--workspace-box: {} values (expected xmin,xmax,ymin,ymax,zmin,zmax in the base frame, m)", box.size()));
    for (const auto& [values, option] : {std::pair{&point, "--workspace-point"}, {&box, "--workspace-box"}}) {
        for (std::size_t i = 0; i < values->size(); ++i) {
            if (!std::isfinite((*values)[i])) throw InputError(fmt::format("{}: value {} is {} (expected a finite number, m)", option, i + 1, (*values)[i]));
        }
    }
    WorkspaceBox b;
    for (int axis = 0; axis < 3; ++axis) {
        b.lower[axis] = box[static_cast<std::size_t>(2 * axis)], b.upper[axis] = box[static_cast<std::size_t>(2 * axis + 1)];
        if (!(b.lower[axis] < b.upper[axis])) {
            throw InputError(fmt::format("--workspace-box: {}min {} >= {}max {} (expected min < max)", kAxes[axis], b.lower[axis], kAxes[axis], b.upper[axis]));
        }
    }
    const NamedFrame named = named_frame(robot, frame);
    Workspace w{FrameKinematics(robot.chain, named.joint, named.offset, Eigen::Vector3d(point[0], point[1], point[2])), b, Eigen::Vector3d::Zero(), frame};
    w.start = w.frame.point(pose, nullptr);
    for (int axis = 0; axis < 3; ++axis) {
        if (!(w.start[axis] > b.lower[axis] && w.start[axis] < b.upper[axis])) {
            throw InputError(fmt::format("--workspace-box: at the start pose the point of frame {} is at {} = {:.6g} m, not strictly inside [{}, {}] (the box must contain it)",
                                         frame, kAxes[axis], w.start[axis], b.lower[axis], b.upper[axis]));
        }
    }
    return w;
}

}  // namespace jacobid::excite
