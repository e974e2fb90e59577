// SPDX-License-Identifier: MIT
#include "excite/regressor_derivatives.hpp"

#include <algorithm>
#include <cmath>

#include "excite/serial_derivative_routes.hpp"

namespace jacobid::excite {
namespace {

// Central differences of any model's regressor.
class CentralDifferences final : public RegressorDerivatives {
public:
    explicit CentralDifferences(const robot::RobotModel& model) : model_(model) {}
    DerivativeRoute route() const override { return DerivativeRoute::CentralDifferences; }

    void evaluate(const double* q0, const double* qd0, const double* qdd0, const Eigen::Ref<const Eigen::MatrixXd>& H, const Eigen::VectorXd& x, Eigen::VectorXd& dphi,
                  Eigen::MatrixXd* dtau) const override {
        constexpr double kStep = 1e-6;
        const int n = model_.joint_count(), p = model_.parameter_count();
        Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(q0, n), qd = Eigen::Map<const Eigen::VectorXd>(qd0, n),
                        qdd = Eigen::Map<const Eigen::VectorXd>(qdd0, n);
        Eigen::MatrixXd Y(n, p), plus(n, p), minus(n, p), d(n, p);
        model_.regressor(q.data(), qd.data(), qdd.data(), Y);
        dphi.setZero(3 * n);
        if (dtau) dtau->resize(n, 3 * n);
        auto store = [&](int lane) {
            if (H.size() > 0) dphi[lane] = H.cwiseProduct(d).sum();
            if (dtau) dtau->col(lane) = d * x;
        };
        auto central = [&](Eigen::VectorXd& v, int j, int lane) {
            const double h = kStep * std::max(1.0, std::abs(v[j]));
            v[j] += h;
            model_.regressor(q.data(), qd.data(), qdd.data(), plus);
            v[j] -= 2.0 * h;
            model_.regressor(q.data(), qd.data(), qdd.data(), minus);
            v[j] += h;
            d = (plus - minus) / (2.0 * h);
            store(lane);
        };
        for (int j = 0; j < n; ++j) {
            central(q, j, j);
            central(qd, j, n + j);
            qdd[j] += 1.0;  // Y is linear in qdd: the difference is the exact derivative
            model_.regressor(q.data(), qd.data(), qdd.data(), plus);
            qdd[j] -= 1.0;
            d = plus - Y;
            store(2 * n + j);
        }
    }

private:
    const robot::RobotModel& model_;
};

}  // namespace

const char* to_string(DerivativeRoute route) {
    switch (route) {
        case DerivativeRoute::Adjoint: return "adjoint";
        case DerivativeRoute::CentralDifferences: return "central";
        case DerivativeRoute::Automatic: return "automatic";
    }
    return "?";
}

std::unique_ptr<RegressorDerivatives> make_regressor_derivatives(const robot::RobotModel& model, DerivativeRoute route) {
    if (const auto* serial = dynamic_cast<const robot::SerialRobotModel*>(&model)) {
        std::unique_ptr<RegressorDerivatives> fixed;
        if (route == DerivativeRoute::Adjoint) fixed = make_adjoint_derivatives(*serial);
        if (route == DerivativeRoute::Automatic) fixed = make_automatic_derivatives(*serial);
        if (fixed) return fixed;
    }
    return std::make_unique<CentralDifferences>(model);
}

}  // namespace jacobid::excite
