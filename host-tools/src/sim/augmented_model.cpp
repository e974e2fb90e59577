// SPDX-License-Identifier: MIT
#include "sim/augmented_model.hpp"

namespace jacobid::sim {

AugmentedModel::AugmentedModel(const robot::RobotModel& nominal, EffectContext context, std::vector<EffectTerm> terms)
    : nominal_(nominal), context_(std::move(context)), names_(nominal.parameter_names()) {
    for (const auto& t : terms) {
        if (t.column_count() == 0) continue;
        terms_.push_back(t);
        first_column_.push_back(static_cast<int>(names_.size()));
        for (auto& name : t.column_names()) names_.push_back(std::move(name));
    }
}

void AugmentedModel::regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const {
    const int c0 = nominal_.parameter_count();
    nominal_.regressor(q, qd, qdd, D.leftCols(c0));
    for (std::size_t t = 0; t < terms_.size(); ++t) {
        term_columns(terms_[t], context_, q, qd, qdd, D.middleCols(first_column_[t], terms_[t].column_count()));
    }
}

}  // namespace jacobid::sim
