// SPDX-License-Identifier: MIT
#pragma once
// A RobotModel decorator: the nominal model's regressor followed by the columns of extra effect terms.
// Everything that works on a RobotModel (ForwardDynamics, the identification pipeline, validation) then
// works on the augmented model unchanged: the simulator integrates the truth with hidden effects, the
// diagnosis identifies nominal and candidate parameters together.
#include <vector>

#include "robot/model_extension.hpp"
#include "sim/effect_terms.hpp"

namespace jacobid::sim {

class AugmentedModel final : public robot::ModelExtension {
public:
    // `nominal` must outlive this model. Terms without columns (torque_delay) are ignored.
    AugmentedModel(const robot::RobotModel& nominal, EffectContext context, std::vector<EffectTerm> terms);
    void regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const override;
    // The nominal model's Coulomb columns and the coulomb_smoothing terms' (the same s(qd_j) at another alpha),
    // so that a candidate sees the velocity and the filter the nominal FCj sees (docs/method.md, "Coulomb columns").
    void coulomb_columns(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const override;
    std::vector<int> coulomb_column_indices() const override;
    // History columns: the nominal model's (presliding friction), then one state per presliding term (its
    // joint's Dahl state at the term's x_p, through the play operator of EffectContext::presliding_play),
    // so that both are fitted beside the other terms.
    int history_size() const override { return nominal().history_size() + static_cast<int>(history_terms_.size()); }
    void integrate_history(const std::vector<const std::vector<double>*>& q, std::vector<double>& state) const override;
    void history_columns(const double* state, Eigen::Ref<Eigen::MatrixXd> D) const override;
    // The nominal model's inverse dynamics plus the terms' columns times their values, when the nominal
    // model has one: the simulator's n + 2 evaluations per step without the full regressor.
    bool inverse_dynamics(const double* q, const double* qd, const double* qdd, const Eigen::VectorXd& X, double* tau) const override;
    // The nominal model's articulated-body forward dynamics with the terms' torques moved to the torque side,
    // when no term depends on qdd (rotor_inertia does: it changes the inertia matrix) and the nominal model
    // has that route; nullptr otherwise, and ForwardDynamics builds the inertia matrix.
    std::unique_ptr<robot::DirectForwardDynamics> articulated_body(const Eigen::VectorXd& X) const override;
    // tau += sum over the terms of their columns at (q, qd, qdd) times their values (X's entries after the
    // nominal parameters). `columns`: scratch (joints x the widest term), resized when too small.
    void add_term_torques(const double* q, const double* qd, const double* qdd, const Eigen::VectorXd& X, Eigen::MatrixXd& columns,
                          double* tau) const;

    const std::vector<EffectTerm>& terms() const { return terms_; }
    // First column of term t in D.
    int term_column(std::size_t t) const { return first_column_[t]; }

private:
    // The coulomb_load terms' load factors at q, evaluated once for all of them (null when there are none).
    const double* load_factors(const double* q) const;

    EffectContext context_;
    std::vector<EffectTerm> terms_;
    std::vector<int> first_column_;
    std::vector<std::size_t> history_terms_;  // indices into terms_ of the presliding terms
    bool load_terms_ = false;                  // some term is coulomb_load
};

}  // namespace jacobid::sim
