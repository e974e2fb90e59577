// SPDX-License-Identifier: MIT
#include "identify/drive_gains/drive_gains_constrained.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "identify/physical/lmi_barrier.hpp"
#include "identify/physical/physical_least_squares.hpp"
#include "identify/physical/physical_parametrization.hpp"

namespace jacobid::identify {
namespace {

// The payload's block: its pseudo-inertia, linear in its ten parameters.
LmiBlock payload_block(int first_column) {
    LmiBlock block;
    block.size = 4;
    for (int k = 0; k < 10; ++k) {
        double ten[10] = {};
        ten[k] = 1.0;
        block.terms.push_back({first_column + k, pseudo_inertia(ten)});
    }
    return block;
}

// A strictly feasible payload: the known values, the unknown centre of mass at the origin and an unknown
// inertia that of a 5 cm solid sphere (any strictly feasible point does: the minimum is global).
Eigen::Matrix<double, 10, 1> payload_start(const PayloadParameters& payload) {
    Eigen::Matrix<double, 10, 1> phi = payload.known;
    const double m = phi[9];
    const Eigen::Vector3d c = phi.segment<3>(6) / m;
    const double sphere = 0.4 * m * 0.05 * 0.05;
    const Eigen::Matrix3d io = sphere * Eigen::Matrix3d::Identity() + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    Eigen::Matrix<double, 6, 1> inertia;
    inertia << io(0, 0), io(0, 1), io(0, 2), io(1, 1), io(1, 2), io(2, 2);
    for (int k : payload.unknown) {
        if (k < 6) phi[k] = inertia[k];
    }
    return phi;
}

}  // namespace

DriveGainEstimate drive_gains_constrained(const DriveGainResult& result, const robot::SerialRobotModel& model,
                                          const robot::RobotDescription& description) {
    const LsSolution& ls = result.method.solution;
    const int c = result.parameter_count, p = result.payload_columns, n = result.joints;
    const int s_count = model.standard_parameter_count();
    const int phi0 = s_count, g0 = s_count + 10, size = s_count + 10 + n;
    std::vector<double> weights = ls.joint_weights;
    if (weights.size() != result.factors.r.size()) weights.assign(result.factors.r.size(), 1.0);
    const Eigen::MatrixXd factor = stacked_factor(result.factors, weights);
    const double sigma2 = std::isfinite(ls.sigma_rho) && ls.sigma_rho > 0.0 ? ls.sigma_rho * ls.sigma_rho : 1.0;

    // The least squares' columns [theta; phi_u; g] as a linear map of the variables [s; phi; g].
    Eigen::MatrixXd map = Eigen::MatrixXd::Zero(c + p + n, size);
    map.topLeftCorner(c, s_count) = model.base().regrouping;
    for (int k = 0; k < p; ++k) map(c + k, phi0 + result.payload.unknown[static_cast<std::size_t>(k)]) = 1.0;
    for (int j = 0; j < n; ++j) map(c + p + j, g0 + j) = 1.0;
    const Eigen::MatrixXd a = factor.leftCols(c + p + n) * map;
    const Eigen::VectorXd z = factor.col(c + p + n);
    Eigen::MatrixXd q = a.transpose() * a / sigma2;
    Eigen::VectorXd lin = a.transpose() * z / sigma2;
    const Eigen::MatrixXd data_q = q;
    const Eigen::VectorXd data_lin = lin;

    // The prior: the description's inertials for the links, 0 for the payload's unknown parameters.
    const PhysicalParametrization robot_set(model.standard_names(), PhysicalConstraint::Full);
    const Eigen::VectorXd given = robot::standard_values(description, model);
    const double w = PhysicalSettings{}.prior_weight;
    const std::vector<int> last = last_link_columns(model);
    for (int l = 0; l < robot_set.link_count(); ++l) {
        for (int k = 0; k < 10; ++k) {
            const int i = robot_set.link_first_column(l) + k;
            const double u = prior_unit(model.standard_names()[static_cast<std::size_t>(i)]);
            q(i, i) += w / (u * u);
            lin[i] += w * given[i] / (u * u);
        }
    }
    // A known parameter is coupled to the rest only through the payload's block (the data term holds it as a
    // constant), so a pin of 1e6 per unit^2 leaves it off by about 1e-6 unit / (t x its barrier slope) at the
    // end: nothing, without the ill-conditioning of a pin scaled to the data term.
    constexpr double stiff = 1e6;
    for (int k = 0; k < 10; ++k) {
        const int i = phi0 + k;
        const bool unknown = std::find(result.payload.unknown.begin(), result.payload.unknown.end(), k) != result.payload.unknown.end();
        const double u = prior_unit(model.standard_names()[static_cast<std::size_t>(last[static_cast<std::size_t>(k)])]);
        const double weight = (unknown ? w : stiff) / (u * u);
        q(i, i) += weight;
        lin[i] += unknown ? 0.0 : weight * result.payload.known[k];
    }

    std::vector<LmiBlock> blocks = robot_set.constraint_blocks();
    blocks.push_back(payload_block(phi0));
    for (int j = 0; j < n; ++j) blocks.push_back({1, {{g0 + j, Eigen::MatrixXd::Ones(1, 1)}}});

    Eigen::VectorXd x0(size);
    x0.head(s_count) = robot_set.standard(robot_set.variables(given));
    x0.segment<10>(phi0) = payload_start(result.payload);
    const Eigen::VectorXd& g_ls = result.least_squares.gains;
    x0.tail(n) = g_ls.cwiseMax(1e-3 * g_ls.cwiseAbs().maxCoeff());
    const Eigen::VectorXd ls_x = ls.x.unaryExpr([](double v) { return std::isnan(v) ? 0.0 : v; });
    const double chi2_ls = (factor.leftCols(c + p + n) * ls_x - z).squaredNorm() / sigma2;
    // The gap relative to the chi^2 (thousands of equations): 1e-6 of it changes no reported digit, while an
    // absolute 1e-6 asks the Newton steps for more digits than the stiff pinned directions leave them.
    BarrierSettings barrier;
    barrier.gap = std::max(barrier.gap, 1e-6 * chi2_ls);
    const BarrierResult solved = minimise_with_lmis(q, lin, blocks, x0, barrier);

    DriveGainEstimate out;
    out.estimator = "constrained";
    out.gains = solved.x.tail(n);
    out.std_dev = Eigen::VectorXd::Constant(n, std::nan(""));
    out.payload = solved.x.segment<10>(phi0);
    out.converged = solved.converged;
    // chi^2 of the data term against the least squares' (the constant z^T z / sigma2 cancels in the difference).
    const auto chi2 = [&](const Eigen::VectorXd& x) { return x.dot(data_q * x) - 2.0 * data_lin.dot(x) + z.squaredNorm() / sigma2; };
    out.note = fmt::format("chi^2 {:.6g} against {:.6g} unconstrained ({:+.3g} %), {} Newton steps, duality gap {:.2g}{}", chi2(solved.x), chi2_ls,
                           100.0 * (chi2(solved.x) - chi2_ls) / chi2_ls, solved.newton_steps, solved.gap, solved.converged ? "" : " (NOT converged)");
    return out;
}

}  // namespace jacobid::identify
