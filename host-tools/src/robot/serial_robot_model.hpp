// SPDX-License-Identifier: MIT
#pragma once
// Host model of a serial (or tree) robot described by MDH rows or a URDF: the fixed-size RNEA regressor of
// the standard parameters (lib/include/jacobid/robot/rnea_regressor.hpp) reduced to the numerically
// computed base parameters (base_parameters.hpp). parameter_names() are the BASE parameters (ZZ1R, XX2R,
// FV1, ...), regressor() is the base regressor; the standard regressor and the regrouping stay available
// for printing the relations and for turning true standard values into true base values.
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "jacobid/robot/kinematic_chain.hpp"
#include "jacobid/robot/rnea_regressor.hpp"
#include "jacobid/robot/standard_parameters.hpp"
#include "robot/base_parameters.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::robot {

constexpr int kMaxSerialJoints = 10;

struct SerialRobotConfig {
    std::string name = "mdh";                // "mdh" or "urdf"
    std::vector<ChainJoint> joints;          // topological order
    Eigen::Vector3d gravity{0.0, 0.0, -9.81};  // m/s^2 in the base frame
    StandardParameterOptions options{};
    std::vector<CoulombSign> joint_coulomb;  // per joint; empty (or shorter): options.coulomb
};

// The lib's fixed-size regressor of a configuration of N joints: its chain, gravity, options and per-joint
// Coulomb functions. std::invalid_argument for an invalid chain.
template <int N>
RneaRegressor<N> make_rnea_regressor(const SerialRobotConfig& config) {
    KinematicChain<N> chain;
    for (std::size_t j = 0; j < config.joints.size(); ++j) {
        const ChainError e = chain.add(config.joints[j]);
        if (e != ChainError::Ok) throw std::invalid_argument("joint " + std::to_string(j + 1) + ": " + to_string(e));
    }
    RneaRegressor<N> regressor(chain, config.gravity, config.options);
    for (std::size_t j = 0; j < config.joint_coulomb.size(); ++j) regressor.set_coulomb(static_cast<int>(j), config.joint_coulomb[j]);
    return regressor;
}

// Standard parameter names in column order for `joints` joints: XX1 XY1 ... FC1 [FOFF1] XX2 ...
std::vector<std::string> standard_parameter_names(int joints, const StandardParameterOptions& options);

class SerialRobotModel final : public RobotModel {
public:
    // Throws std::invalid_argument for an invalid chain (more than kMaxSerialJoints joints, bad antecedent, ...).
    explicit SerialRobotModel(SerialRobotConfig config, const BaseParameterSettings& base_settings = {});
    ~SerialRobotModel() override;

    std::string model_name() const override { return config_.name; }
    int joint_count() const override { return static_cast<int>(config_.joints.size()); }
    int parameter_count() const override { return static_cast<int>(base_.base_columns.size()); }
    const std::vector<std::string>& parameter_names() const override { return base_.base_names; }
    void regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const override;
    // The FCj base columns alone (each the standard FC column of its joint: s_j(qd_j) in row j).
    void coulomb_columns(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const override;
    // Newton-Euler with the base values placed on their standard columns (W_std X* = W_base X): exact, O(n).
    bool inverse_dynamics(const double* q, const double* qd, const double* qdd, const Eigen::VectorXd& X, double* tau) const override;
    // Featherstone's articulated-body algorithm on the same standard vector (base values on their columns):
    // the regrouped inertias give the same M(q) and hence the same qdd as the inertia-matrix route.
    std::unique_ptr<DirectForwardDynamics> articulated_body(const Eigen::VectorXd& X) const override;

    const SerialRobotConfig& config() const { return config_; }
    int standard_parameter_count() const { return static_cast<int>(standard_names_.size()); }
    const std::vector<std::string>& standard_names() const { return standard_names_; }
    int standard_index(const std::string& name) const;
    void standard_regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> W) const;
    const BaseParameterSet& base() const { return base_; }
    // base = regrouping * standard; a value that cancels to rounding level of its terms (XX6R = XX6 - YY6 of a
    // symmetric link) is exactly 0, so that reports do not show relative errors against 1e-20.
    Eigen::VectorXd base_values(const Eigen::VectorXd& standard) const;
    std::vector<std::string> relations() const { return regrouping_relations(base_, standard_names_); }

    // Per joint count N, the fixed-size regressor (an implementation detail of the .cpp).
    class Evaluator;

private:
    SerialRobotConfig config_;
    std::vector<std::string> standard_names_;
    std::unique_ptr<Evaluator> evaluator_;
    std::vector<std::pair<int, int>> coulomb_columns_;  // (base column, joint) of every FCj base column
    BaseParameterSet base_;
};

}  // namespace jacobid::robot
