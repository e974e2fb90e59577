// SPDX-License-Identifier: MIT
#pragma once
// `jacobid excite --workspace-frame F --workspace-point x,y,z --workspace-box xmin,xmax,..` (docs/excite.md,
// "Workspace box"): a point fixed in a frame of the robot kept inside an axis-aligned box of the base frame.
// The box's six faces are constraints like the joints' position limits: each face's room is measured from
// the point at the start pose, the optimizer sees the faces moved toward it by the same margin, and the
// same tightening rounds move a face that the point crossed between the optimizer's samples.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <string>

#include "excite/fourier_trajectory.hpp"
#include "excite/frame_kinematics.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::excite {

// Faces indexed 2 * axis + side: 0 x max, 1 x min, 2 y max, 3 y min, 4 z max, 5 z min.
constexpr int kBoxFaces = 6;
const char* face_name(int face);

struct WorkspaceBox {
    Eigen::Vector3d lower = Eigen::Vector3d::Zero(), upper = Eigen::Vector3d::Zero();  // m, base frame
};

// Room of a face from the start point (> 0 when the start is inside): upper - start or start - lower.
double face_room(const WorkspaceBox& box, const Eigen::Vector3d& start, int face);
// The box with each face's room from `start` scaled by factors[face] (the margin and the tightening rounds).
WorkspaceBox shrink_toward(const WorkspaceBox& box, const Eigen::Vector3d& start, const std::array<double, kBoxFaces>& factors);

// The constraint as the problem holds it: the frame's point, the box, the point at the start pose, and the
// names the outputs show.
struct Workspace {
    FrameKinematics frame;
    WorkspaceBox box;
    Eigen::Vector3d start;
    std::string frame_name;  // as given to --workspace-frame
};

// The point at every control sample of one period (rate in Hz): its extremes and each face's use (excursion
// from the start toward the face over the room; <= 1 inside).
struct WorkspaceCheck {
    Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();
    std::array<double, kBoxFaces> ratio{};
    double worst = 0.0;
    int worst_face = 0;
    std::size_t worst_sample = 0;
};
WorkspaceCheck check_workspace(const Workspace& workspace, const FourierTrajectory& trajectory, double rate);

// The command line's workspace: `frame` is a joint number 1..n (that joint's frame), `tool` or `last` (joint
// n's frame), or, for a URDF robot, a link name (its frame, fixed to the link of the joint that carries it);
// point in that frame (m), box {xmin, xmax, ymin, ymax, zmin, zmax} in the base frame (m). InputError naming
// the option: an unknown frame, a link fixed to the base, min >= max, a value that is not finite, or the
// point at `pose` not strictly inside the box.
Workspace make_workspace(const robot::RobotDescription& robot, const std::string& frame, const std::vector<double>& point,
                         const std::vector<double>& box, const Eigen::VectorXd& pose);

}  // namespace jacobid::excite
