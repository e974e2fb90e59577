// SPDX-License-Identifier: MIT
#include "identify/physical/lmi_barrier.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace jacobid::identify {

Eigen::MatrixXd LmiBlock::at(const Eigen::VectorXd& x) const {
    Eigen::MatrixXd F = Eigen::MatrixXd::Zero(size, size);
    for (const Term& t : terms) F += x[t.column] * t.matrix;
    return F;
}

namespace {

// -sum log det F_i(x); +infinity when a block is not positive definite.
double barrier(const std::vector<LmiBlock>& blocks, const Eigen::VectorXd& x) {
    double b = 0.0;
    for (const LmiBlock& block : blocks) {
        const Eigen::LLT<Eigen::MatrixXd> llt(block.at(x));
        if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
        const Eigen::VectorXd d = llt.matrixLLT().diagonal();
        if (!(d.minCoeff() > 0.0)) return std::numeric_limits<double>::infinity();
        b -= 2.0 * d.array().log().sum();
    }
    return b;
}

// Newton decrement (squared) below which a round counts as centred: inside the region where the
// self-concordance bound (suboptimality <= decrement) holds.
constexpr double kCentredDecrement = 0.25;

}  // namespace

BarrierResult minimise_with_lmis(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c, const std::vector<LmiBlock>& blocks, Eigen::VectorXd x,
                                 const BarrierSettings& settings) {
    if (!std::isfinite(barrier(blocks, x))) throw std::invalid_argument("minimise_with_lmis: the start is not strictly feasible");
    auto objective = [&](const Eigen::VectorXd& v) { return v.dot(Q * v) - 2.0 * c.dot(v); };
    double degree = 0.0;
    for (const LmiBlock& block : blocks) degree += block.size;

    BarrierResult r;
    // t so that the first round weighs the objective and the barrier alike.
    double t = degree / std::max(1.0, std::abs(objective(x)));
    const double ridge = 1e-14 * std::max(1.0, Q.diagonal().cwiseAbs().maxCoeff());
    while (true) {
        // Newton on t f + barrier. `decrement` ends as the Newton decrement (squared) of the round's last point:
        // the centring problem's suboptimality bound (for a self-concordant barrier, while it is below ~0.68^2).
        double decrement = std::numeric_limits<double>::infinity();
        for (int inner = 0; inner < 200 && r.newton_steps < settings.max_newton; ++inner, ++r.newton_steps) {
            Eigen::MatrixXd H = 2.0 * t * Q;
            H.diagonal().array() += t * ridge;
            Eigen::VectorXd g = 2.0 * t * (Q * x - c);
            for (const LmiBlock& block : blocks) {
                const Eigen::MatrixXd Finv = block.at(x).llt().solve(Eigen::MatrixXd::Identity(block.size, block.size));
                std::vector<Eigen::MatrixXd> P;  // F^-1 F_k
                P.reserve(block.terms.size());
                for (const auto& term : block.terms) P.push_back(Finv * term.matrix);
                for (std::size_t a = 0; a < block.terms.size(); ++a) {
                    g[block.terms[a].column] -= P[a].trace();
                    for (std::size_t b = a; b < block.terms.size(); ++b) {
                        const double h = (P[a].cwiseProduct(P[b].transpose())).sum();  // tr(P_a P_b)
                        H(block.terms[a].column, block.terms[b].column) += h;
                        if (b != a) H(block.terms[b].column, block.terms[a].column) += h;
                    }
                }
            }
            const Eigen::VectorXd step = H.ldlt().solve(-g);
            decrement = -g.dot(step);  // Newton decrement squared
            if (!std::isfinite(decrement) || decrement < 0.0) {
                decrement = std::numeric_limits<double>::infinity();  // a singular or indefinite Newton system: not centred
                break;
            }
            if (decrement <= 1e-10) break;
            // The change of t f + barrier along the step, with the objective's change computed as a difference
            // (d^T Q (2 x + d) - 2 c^T d), not as f(x + d) - f(x): late rounds have t f ~ 1e10 and more, where the
            // subtraction would lose the very decrease the line search looks for (and stall the round).
            const double barrier_here = barrier(blocks, x);
            const Eigen::VectorXd anchor = 2.0 * x;
            auto change = [&](const Eigen::VectorXd& d, const Eigen::VectorXd& trial) {
                return t * (d.dot(Q * (anchor + d)) - 2.0 * c.dot(d)) + (barrier(blocks, trial) - barrier_here);
            };
            double alpha = 1.0;
            Eigen::VectorXd trial = x + step;
            double delta = change(step, trial);
            while (!(delta <= -0.25 * alpha * decrement) && alpha > 1e-12) {
                alpha *= 0.5;
                trial = x + alpha * step;
                delta = change(alpha * step, trial);
            }
            if (alpha <= 1e-12) break;  // no progress to rounding
            x = trial;
        }
        // Only a (nearly) centred point carries the certificate: f(x) - f* <= (degree + decrement) / t. A round
        // that stalled away from its centre (line search at rounding, step limit) ends the solve unconverged.
        r.gap = (degree + decrement) / t;
        if (!(decrement <= kCentredDecrement)) break;
        if (r.gap <= settings.gap) {
            r.converged = true;
            break;
        }
        if (r.newton_steps >= settings.max_newton) break;
        t *= 20.0;
    }
    r.objective = objective(x);
    r.x = std::move(x);
    return r;
}

}  // namespace jacobid::identify
