// SPDX-License-Identifier: MIT
#pragma once
// The presliding friction a simulated robot feels (docs/method.md, "Presliding friction (Dahl)"): each Dahl
// state of a model (a PreslidingModel's, one per joint, and an injected presliding effect's) integrated along
// the true positions (no quantization, no play), its joint feeling FD s. Shared by `simulate` and by the
// reference simulations of IDIM-IV and DIDIM, so that the model simulated along a log holds the friction
// the identified FDj say.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "jacobid/robot/presliding_friction.hpp"
#include "robot/robot_model.hpp"
#include "sim/closed_loop.hpp"

namespace jacobid::sim {

class DahlFriction final : public HeldFriction {
public:
    void add(int joint, double displacement, double level);
    bool empty() const { return dahl_.empty(); }
    void step(const Eigen::VectorXd& before, const Eigen::VectorXd& after, Eigen::VectorXd& torque) override;

private:
    std::vector<int> joint_;
    std::vector<robot::DahlState> dahl_;
    std::vector<double> level_;
};

// The presliding friction of `model` at `parameters`, every state starting at 0 (nullptr when it has none).
std::unique_ptr<DahlFriction> presliding_friction(const robot::RobotModel& model, const Eigen::VectorXd& parameters);

}  // namespace jacobid::sim
