// SPDX-License-Identifier: MIT
#pragma once
// The prior scale of every base parameter (what a-relative and e-relative divide each predicted std by,
// and what the predicted relative std of excite's output is relative to; docs/excite.md "Prior scales"):
//   s_k = max(|x_k|, P_k / 10), x_k the prior value, P_k a physical scale of the parameter's kind:
//   - inertias (XX.. ZZ, with or without R) and rotor inertias IA: m_j l^2;
//   - first moments (MX, MY, MZ): m_j l;  masses (M): m_j;
//   - Coulomb friction and offsets (FC, FOFF): the joint's friction level F_j; viscous friction (FV): F_j per rad/s;
//   where j is the joint in the parameter's name, m_j the mass joint j carries (the description's standard
//   masses M_j..M_n; 1 kg per link when the model has none), l the mean distance between consecutive joint
//   origins (0.05 m at least; the planar 2R: L1), F_j = max(|FC_j|, |FV_j| x 1 rad/s, |FOFF_j|) of the prior,
//   or 1 % of m_j g l when all three are 0. A parameter of another kind: max(|x_k|, 1).
// So a parameter whose prior is 0 (or tiny) is judged against a tenth of what its kind weighs on that joint.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::excite {

// The physical scale P_k of every base parameter of `model` (names as the model gives them).
Eigen::VectorXd physical_scales(const robot::RobotDescription& description, const robot::RobotModel& model, const Eigen::VectorXd& prior);

// s_k = max(|x_k|, P_k / 10).
Eigen::VectorXd prior_scales(const robot::RobotDescription& description, const robot::RobotModel& model, const Eigen::VectorXd& prior);

}  // namespace jacobid::excite
