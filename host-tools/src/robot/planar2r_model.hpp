// SPDX-License-Identifier: MIT
#pragma once
// Host adapter of the fixed-size 2R regressor (lib/include/jacobid/robot/planar2r.hpp).
#include "jacobid/robot/planar2r.hpp"
#include <vector>

#include "robot/robot_model.hpp"

namespace jacobid::robot {

class Planar2RModel final : public RobotModel {
public:
    // joint_coulomb: per-joint Coulomb sign functions (empty: config.coulomb for both joints).
    explicit Planar2RModel(const Planar2RConfig& config, const std::vector<CoulombSign>& joint_coulomb = {});
    std::string model_name() const override { return "planar2r"; }
    int joint_count() const override { return Planar2R::kJoints; }
    int parameter_count() const override { return model_.parameter_count(); }
    const std::vector<std::string>& parameter_names() const override { return names_; }
    void regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const override;
    const Planar2R& fixed_size_model() const { return model_; }

private:
    Planar2R model_;
    std::vector<std::string> names_;
};

// The paper's Table II (Jacobi column), used as the default truth of the simulator; optional parameters
// (offsets, rotor inertia) default to 0.
std::vector<double> paper_table2_parameters(const Planar2RModel& model);

}  // namespace jacobid::robot
