// SPDX-License-Identifier: MIT
#pragma once
// The base of every model that extends a nominal model with columns after the nominal's: load-dependent
// Coulomb friction (load_friction_model.hpp), presliding friction (presliding_model.hpp) and the simulator's
// and the diagnosis's hidden effects (sim/augmented_model.hpp). It forwards what such a model does not change
// (name, joints, whether the regressor may run on several threads) and keeps the parameter names: the
// nominal's, then the appended ones. The nominal model is borrowed (it must outlive this one) or owned.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "robot/robot_model.hpp"

namespace jacobid::robot {

class ModelExtension : public RobotModel {
public:
    std::string model_name() const override { return nominal_->model_name(); }
    int joint_count() const override { return nominal_->joint_count(); }
    int parameter_count() const override { return static_cast<int>(names_.size()); }
    const std::vector<std::string>& parameter_names() const override { return names_; }
    bool concurrent_regressor() const override { return nominal_->concurrent_regressor(); }

    const RobotModel& nominal() const { return *nominal_; }
    // Columns of the nominal model: the appended ones start here.
    int nominal_parameter_count() const { return nominal_->parameter_count(); }

protected:
    explicit ModelExtension(const RobotModel& nominal) : nominal_(&nominal), names_(nominal.parameter_names()) {}
    explicit ModelExtension(std::unique_ptr<RobotModel> nominal)
        : owned_(std::move(nominal)), nominal_(owned_.get()), names_(nominal_->parameter_names()) {}

    // A column after the nominal's and the ones appended before it.
    void append_parameter(std::string name) { names_.push_back(std::move(name)); }

private:
    std::unique_ptr<RobotModel> owned_;  // empty when borrowed
    const RobotModel* nominal_;
    std::vector<std::string> names_;
};

}  // namespace jacobid::robot
