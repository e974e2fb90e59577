// SPDX-License-Identifier: MIT
#pragma once
// A robot model with Dahl presliding friction (docs/method.md, "Presliding friction (Dahl)"): the nominal
// model's columns followed by one column FDj per joint, the joint's Dahl state s_j in [-1, 1] on its own
// row (friction torque FDj s_j, linear in FDj like FCj, FVj, FOFFj). The state is a function of the
// position path, so these are history columns (RobotModel::history_size): integrated once per log along
// the raw logged positions through a play operator that removes quantization flicker, then written into
// each sample's regressor row, upstream of F_p like every other column.
#include <memory>
#include <string>
#include <vector>

#include "robot/model_extension.hpp"

namespace jacobid::robot {

struct PreslidingSettings {
    std::vector<double> displacement;  // x_p per joint, rad (> 0)
    double play_width = 2e-4;          // rad: total width of the play operator's band (two UR10e quantization steps); 0: raw positions
    // s at the first sample, per joint (empty: 0 for all). Unknown in general: the neutral 0 when identifying
    // (the state saturates within the first x_p of motion); validation estimates it from the held torque at
    // the log's start (identify/validation/validation.cpp), as an observer would.
    std::vector<double> initial_state;
};

class PreslidingModel final : public ModelExtension {
public:
    // `nominal` must outlive this model when borrowed; owned when given as unique_ptr.
    PreslidingModel(std::unique_ptr<RobotModel> nominal, PreslidingSettings settings);
    PreslidingModel(const RobotModel& nominal, PreslidingSettings settings);

    void regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const override;
    void coulomb_columns(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const override;
    // The nominal model's, on its parameters: the presliding columns are history columns, 0 in a stateless
    // evaluation, and the simulator applies them as held friction (sim/simulator.cpp).
    std::unique_ptr<DirectForwardDynamics> articulated_body(const Eigen::VectorXd& X) const override {
        return nominal().articulated_body(X.head(nominal_parameter_count()));
    }
    int history_size() const override { return joint_count(); }
    void integrate_history(const std::vector<const std::vector<double>*>& q, std::vector<double>& state) const override;
    void history_columns(const double* state, Eigen::Ref<Eigen::MatrixXd> D) const override;

    const PreslidingSettings& settings() const { return settings_; }
    int first_presliding_column() const { return nominal_parameter_count(); }

private:
    // The settings checked against the nominal model, then its FDj columns appended.
    void add_presliding_columns();

    PreslidingSettings settings_;
};

// The model without its presliding and load-dependent friction columns (itself when it has none): what
// regrouping and plausibility checks of the rigid-body parameters look at. The appended columns come last
// (FCLj, then FDj).
const RobotModel& rigid_body(const RobotModel& model);

// One joint's Dahl state along a position column (the play operator of total width `play_width`, then
// the exact Dahl update; presliding_friction.hpp).
std::vector<double> presliding_states(const std::vector<double>& q, double displacement, double play_width, double initial_state = 0.0);

}  // namespace jacobid::robot
