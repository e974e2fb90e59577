// SPDX-License-Identifier: MIT
#include "robot/planar2r_model.hpp"

namespace jacobid::robot {

Planar2RModel::Planar2RModel(const Planar2RConfig& config, const std::vector<CoulombSign>& joint_coulomb) : model_(config) {
    for (std::size_t j = 0; j < joint_coulomb.size(); ++j) model_.set_coulomb(static_cast<int>(j), joint_coulomb[j]);
    for (int c = 0; c < model_.parameter_count(); ++c) names_.emplace_back(model_.parameter_name(c));
}

void Planar2RModel::regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const {
    Planar2R::Regressor fixed;
    model_.regressor(Planar2R::Joints(q[0], q[1]), Planar2R::Joints(qd[0], qd[1]), Planar2R::Joints(qdd[0], qdd[1]), fixed);
    D = fixed.leftCols(model_.parameter_count());
}

std::vector<double> paper_table2_parameters(const Planar2RModel& model) {
    using P = Planar2R::Parameter;
    std::vector<double> x(static_cast<std::size_t>(model.parameter_count()), 0.0);
    const std::pair<P, double> table[] = {{P::ZZ1R, 3.496}, {P::FV1, 0.248}, {P::FC1, 0.431},  {P::ZZ2, 0.059},
                                          {P::MX2, 0.124},  {P::MY2, 0.0019}, {P::FV2, 0.0144}, {P::FC2, 0.1268}};
    for (const auto& [parameter, value] : table) {
        const int c = model.fixed_size_model().column(parameter);
        if (c >= 0) x[static_cast<std::size_t>(c)] = value;
    }
    return x;
}

}  // namespace jacobid::robot
