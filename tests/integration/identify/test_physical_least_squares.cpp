// SPDX-License-Identifier: MIT
// Physically consistent least squares (identify/physical/physical_parametrization.hpp, physical_least_squares.hpp),
// checked against independent facts: the pseudo-inertia of a uniform box from its closed form, the
// triangle inequalities computed from eigenvalues of the inertia about the centre of mass, and optimality of
// the constrained solution by brute force (the problem is convex in the standard parameters, so no feasible
// point on the segment towards any other feasible point may lower the cost).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <limits>
#include <random>

#include "identify/physical/lmi_barrier.hpp"
#include "identify/physical/physical_least_squares.hpp"
#include "identify/physical/physical_parametrization.hpp"

namespace {

using namespace jacobid::identify;

const std::vector<std::string> kLinkNames = {"XX1", "XY1", "XZ1", "YY1", "YZ1", "ZZ1", "MX1", "MY1", "MZ1", "M1", "IA1", "FV1", "FC1", "FOFF1"};

// A random rigid body: mass, centre of mass, principal moments that satisfy the triangle inequalities (a
// box of random sides), a random orientation; its ten standard parameters about the frame origin.
Eigen::Matrix<double, 10, 1> random_body(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.05, 1.0), c(-0.3, 0.3);
    const double m = 10.0 * u(rng), a = u(rng), b = u(rng), h = u(rng);
    const Eigen::Vector3d principal = m / 12.0 * Eigen::Vector3d(b * b + h * h, a * a + h * h, a * a + b * b);
    const Eigen::Matrix3d R = Eigen::Quaterniond(Eigen::Vector4d::Random().normalized()).toRotationMatrix();
    const Eigen::Vector3d com(c(rng), c(rng), c(rng));
    const Eigen::Matrix3d I = R * principal.asDiagonal() * R.transpose() + m * (com.squaredNorm() * Eigen::Matrix3d::Identity() - com * com.transpose());
    Eigen::Matrix<double, 10, 1> ten;
    ten << I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2), m * com[0], m * com[1], m * com[2], m;
    return ten;
}

Eigen::Vector3d inertia_eigenvalues_about_com(const Eigen::VectorXd& s) {
    Eigen::Matrix3d I;
    I << s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5];
    const Eigen::Vector3d c = Eigen::Vector3d(s[6], s[7], s[8]) / s[9];
    const Eigen::Matrix3d Ic = I - s[9] * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Ic).eigenvalues();
}

TEST(PhysicalParametrization, PseudoInertiaOfAUniformBoxIsItsSecondMoment) {
    // Box of sides a, b, c centred at (x0, 0, 0), mass m: Sigma = int r r^T dm = m diag(a^2/12 + x0^2, b^2/12, c^2/12).
    const double m = 3.0, a = 0.4, b = 0.2, c = 0.1, x0 = 0.5;
    double ten[10] = {m * (b * b + c * c) / 12.0, 0, 0, m * (a * a + c * c) / 12.0 + m * x0 * x0, 0, m * (a * a + b * b) / 12.0 + m * x0 * x0,
                      m * x0, 0, 0, m};
    const Eigen::Matrix4d J = pseudo_inertia(ten);
    EXPECT_NEAR(J(0, 0), m * (a * a / 12.0 + x0 * x0), 1e-12);
    EXPECT_NEAR(J(1, 1), m * b * b / 12.0, 1e-12);
    EXPECT_NEAR(J(2, 2), m * c * c / 12.0, 1e-12);
    EXPECT_NEAR(J(0, 3), m * x0, 1e-12);
    EXPECT_NEAR(J(3, 3), m, 1e-12);
    double back[10];
    from_pseudo_inertia(J, back);
    for (int k = 0; k < 10; ++k) EXPECT_NEAR(back[k], ten[k], 1e-12) << k;
}

TEST(PhysicalParametrization, FeasiblePointsRoundTripThroughTheVariables) {
    std::mt19937 rng(7);
    for (const auto constraint : {PhysicalConstraint::Full, PhysicalConstraint::Semi}) {
        const PhysicalParametrization map(kLinkNames, constraint);
        ASSERT_EQ(map.variable_count(), 14);
        for (int trial = 0; trial < 50; ++trial) {
            Eigen::VectorXd s(14);
            s.head<10>() = random_body(rng);
            s.tail<4>() << 0.02, 0.5, 1.5, -0.7;
            const Eigen::VectorXd back = map.standard(map.variables(s, 0.0, 0.0));
            EXPECT_LT((back - s).cwiseAbs().maxCoeff(), 1e-9 * s.cwiseAbs().maxCoeff()) << to_string(constraint) << " trial " << trial;
        }
    }
}

TEST(PhysicalParametrization, AnyVariablesGiveABodyFullAlsoKeepsTheTriangleInequalities) {
    std::mt19937 rng(11);
    std::normal_distribution<double> n(0.0, 1.5);
    int semi_triangle_violations = 0;
    for (int trial = 0; trial < 400; ++trial) {
        Eigen::VectorXd v(14);
        for (int k = 0; k < 14; ++k) v[k] = n(rng);
        for (const auto constraint : {PhysicalConstraint::Full, PhysicalConstraint::Semi}) {
            const Eigen::VectorXd s = PhysicalParametrization(kLinkNames, constraint).standard(v);
            ASSERT_GT(s[9], 0.0);
            const Eigen::Vector3d l = inertia_eigenvalues_about_com(s);  // ascending
            EXPECT_GT(l[0], 0.0);
            EXPECT_GE(s[10], 0.0);
            EXPECT_GE(s[11], 0.0);
            EXPECT_GE(s[12], 0.0);
            const bool triangle = l[0] + l[1] >= l[2] * (1.0 - 1e-9);
            if (constraint == PhysicalConstraint::Full) EXPECT_TRUE(triangle) << "trial " << trial << ": " << l.transpose();
            else semi_triangle_violations += !triangle;
        }
    }
    // The semi-physical set is larger: some of its bodies break the triangle inequalities.
    EXPECT_GT(semi_triangle_violations, 0);
}

// A one-link problem: base = standard (14 columns), a random well-conditioned factor, data from `truth`.
struct Problem {
    Eigen::MatrixXd factor, regrouping;
    Eigen::VectorXd unconstrained;
};

Problem make_problem(const Eigen::VectorXd& truth, unsigned seed, int rows = 400, double noise = 1e-3) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0.0, 1.0);
    const Eigen::Index p = truth.size();
    Eigen::MatrixXd W(rows, p + 1);
    for (int r = 0; r < rows; ++r)
        for (Eigen::Index c = 0; c < p; ++c) W(r, c) = n(rng);
    W.col(p) = W.leftCols(p) * truth;
    for (int r = 0; r < rows; ++r) W(r, p) += noise * n(rng);
    Problem pr;
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(W);
    pr.factor = qr.matrixQR().topRows(p + 1).triangularView<Eigen::Upper>();
    pr.regrouping = Eigen::MatrixXd::Identity(p, p);
    pr.unconstrained = W.leftCols(p).colPivHouseholderQr().solve(W.col(p));
    return pr;
}

double data_cost(const Problem& pr, const Eigen::VectorXd& s) {
    const Eigen::Index c = pr.regrouping.rows();
    return (pr.factor.topLeftCorner(c + 1, c) * pr.regrouping * s - pr.factor.col(c)).squaredNorm();
}

TEST(PhysicalLeastSquares, AFeasibleTruthIsReproducedAsTheUnconstrainedFit) {
    std::mt19937 rng(3);
    Eigen::VectorXd truth(14);
    truth.head<10>() = random_body(rng);
    truth.tail<4>() << 0.05, 0.8, 1.2, 0.3;
    const Problem pr = make_problem(truth, 5);
    PhysicalSettings settings;
    settings.prior_weight = 1e-9;
    const PhysicalFit fit = solve_physical(pr.factor, 1.0, pr.regrouping, kLinkNames, pr.unconstrained, settings);
    EXPECT_TRUE(fit.converged);
    EXPECT_TRUE(fit.active.empty()) << fit.active.front();
    EXPECT_LT((fit.base - pr.unconstrained).cwiseAbs().maxCoeff(), 1e-6);
    EXPECT_NEAR(fit.data_cost, fit.unconstrained_data_cost, 1e-9 * std::max(1.0, fit.unconstrained_data_cost));
}

// Brute-force optimality: f convex, the feasible set convex, so f(s + t (s' - s)) >= f(s) for every feasible
// s' and t in (0, 1]; tried for thousands of random bodies s' and several t.
void expect_optimal(const Problem& pr, const PhysicalFit& fit, PhysicalConstraint constraint, unsigned seed) {
    const PhysicalParametrization map(kLinkNames, constraint);
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0.0, 2.0);
    const double f0 = data_cost(pr, fit.standard);
    double worst = 0.0;
    for (int trial = 0; trial < 3000; ++trial) {
        Eigen::VectorXd v(14);
        for (int k = 0; k < 14; ++k) v[k] = n(rng);
        const Eigen::VectorXd other = map.standard(v);
        for (const double t : {1e-4, 1e-3, 1e-2, 0.1, 1.0}) worst = std::min(worst, data_cost(pr, fit.standard + t * (other - fit.standard)) - f0);
    }
    EXPECT_GT(worst, -1e-6 * std::max(1.0, f0)) << "a feasible point lowers the cost by " << -worst;
}

TEST(PhysicalLeastSquares, AnImpossibleTruthEndsOnTheBoundaryAtTheConstrainedOptimum) {
    std::mt19937 rng(9);
    Eigen::VectorXd truth(14);
    truth.head<10>() = random_body(rng);
    truth[5] = -0.5 * std::abs(truth[5]);  // ZZ1 < 0: no body has it
    truth.tail<4>() << -0.02, -0.3, 1.0, 0.2;  // a negative rotor inertia and viscous coefficient
    const Problem pr = make_problem(truth, 13);
    for (const auto constraint : {PhysicalConstraint::Full, PhysicalConstraint::Semi}) {
        PhysicalSettings settings;
        settings.constraint = constraint;
        settings.prior_weight = 1e-9;
        const PhysicalFit fit = solve_physical(pr.factor, 1.0, pr.regrouping, kLinkNames, pr.unconstrained, settings);
        EXPECT_TRUE(fit.converged) << to_string(constraint);
        EXPECT_GT(fit.data_cost, fit.unconstrained_data_cost);
        bool ia = false, fv = false, link = false;
        for (const auto& a : fit.active) {
            ia = ia || a == "IA1 at 0";
            fv = fv || a == "FV1 at 0";
            link = link || a.rfind("link 1 ", 0) == 0;
        }
        EXPECT_TRUE(ia && fv && link) << to_string(constraint) << ": " << fit.active.size() << " active";
        EXPECT_GT(inertia_eigenvalues_about_com(fit.standard)[0], -1e-9);
        expect_optimal(pr, fit, constraint, 21);
    }
}

TEST(PhysicalLeastSquares, TheProjectedUnconstrainedSolutionIsFeasibleButWorse) {
    std::mt19937 rng(17);
    Eigen::VectorXd truth(14);
    truth.head<10>() = random_body(rng);
    truth[9] = -1.0;  // negative mass
    truth.tail<4>() << 0.01, 0.2, -0.1, 0.0;
    const Problem pr = make_problem(truth, 19);
    const PhysicalFit fit = solve_physical(pr.factor, 1.0, pr.regrouping, kLinkNames, pr.unconstrained, PhysicalSettings{});
    const PhysicalParametrization map(kLinkNames, PhysicalConstraint::Full);
    EXPECT_GE(map.link_relative_min_eigenvalue(fit.projected_standard, 0), 0.0);
    EXPECT_LE(fit.data_cost, data_cost(pr, fit.projected_standard));
}

// Directions that neither the log nor a prior decides (an mdh description without values, a link the log
// does not move) must stay where the data left them: a barrier without an anchor pushes them to infinity.
TEST(PhysicalLeastSquares, UnexcitedDirectionsWithoutAPriorStayAtTheProjectedSolution) {
    std::mt19937 rng(23);
    Eigen::VectorXd truth(14);
    truth.head<10>() = random_body(rng);
    truth.tail<4>() << 0.05, 0.8, 1.2, 0.3;
    Problem full = make_problem(truth, 29);
    // The log sees only the first moments, the mass and the friction (8 base columns = those standard ones).
    const std::vector<int> seen = {6, 7, 8, 9, 10, 11, 12, 13};
    Problem pr;
    pr.regrouping = Eigen::MatrixXd::Zero(8, 14);
    for (int b = 0; b < 8; ++b) pr.regrouping(b, seen[static_cast<std::size_t>(b)]) = 1.0;
    // The factor of those columns' problem: rows of the full data restricted to them.
    std::mt19937 rows_rng(31);
    std::normal_distribution<double> n(0.0, 1.0);
    Eigen::MatrixXd W(300, 9);
    for (int r = 0; r < 300; ++r) {
        for (int b = 0; b < 8; ++b) W(r, b) = n(rows_rng);
        W(r, 8) = 0.0;
        for (int b = 0; b < 8; ++b) W(r, 8) += W(r, b) * truth[seen[static_cast<std::size_t>(b)]];
        W(r, 8) += 1e-3 * n(rows_rng);
    }
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(W);
    pr.factor = qr.matrixQR().topRows(9).triangularView<Eigen::Upper>();
    pr.unconstrained = W.leftCols(8).colPivHouseholderQr().solve(W.col(8));
    for (const double weight : {0.0, 1e-3}) {
        PhysicalSettings settings;  // no prior at all
        settings.prior_weight = weight;
        const PhysicalFit fit = solve_physical(pr.factor, 1.0, pr.regrouping, kLinkNames, pr.unconstrained, settings);
        EXPECT_TRUE(fit.converged) << "weight " << weight;
        ASSERT_TRUE(fit.standard.allFinite());
        // The inertia the log does not see stays of the size the data's mass and first moments need, not
        // pushed outwards by the barrier.
        const double scale = fit.projected_standard.head<6>().cwiseAbs().maxCoeff();
        EXPECT_LT(fit.standard.head<6>().cwiseAbs().maxCoeff(), 3.0 * scale) << "weight " << weight;
        // Every direction the log sees keeps its least-squares value when no prior competes with it.
        if (weight == 0.0) {
            EXPECT_LT((fit.base - pr.unconstrained).cwiseAbs().maxCoeff(), 1e-4);
        }
    }
}

// --semi-physical from a fit with a negative mass and large first moments: the start must not put the
// centre of mass at h / (tiny mass), and the solve must end converged on a possible body.
TEST(PhysicalLeastSquares, SemiPhysicalFromANegativeMassStartsAndConverges) {
    std::mt19937 rng(37);
    Eigen::VectorXd truth(14);
    truth.head<10>() = random_body(rng);
    truth[6] = 2.0, truth[7] = -1.5, truth[8] = 0.7, truth[9] = -0.5;  // h large, m < 0
    truth.tail<4>() << 0.01, 0.2, 0.1, 0.0;
    const Problem pr = make_problem(truth, 41);
    PhysicalSettings settings;
    settings.constraint = PhysicalConstraint::Semi;
    const PhysicalFit fit = solve_physical(pr.factor, 1.0, pr.regrouping, kLinkNames, pr.unconstrained, settings);
    EXPECT_TRUE(fit.converged);
    EXPECT_LT(fit.projected_standard.head<6>().cwiseAbs().maxCoeff(), 1e3) << "the start's inertia blew up";
    EXPECT_GT(fit.standard[9], 0.0);
    EXPECT_GT(inertia_eigenvalues_about_com(fit.standard)[0], 0.0);
    expect_optimal(pr, fit, PhysicalConstraint::Semi, 43);
}

// A Newton system that cannot be solved (here a NaN in the objective) leaves the point uncentred: the
// duality-gap certificate does not hold there, so the solve must not say it converged.
TEST(LmiBarrier, AStalledRoundIsNotReportedConverged) {
    Eigen::MatrixXd Q = Eigen::MatrixXd::Identity(2, 2);
    Q(0, 1) = Q(1, 0) = std::numeric_limits<double>::quiet_NaN();
    const Eigen::VectorXd c = Eigen::VectorXd::Ones(2);
    std::vector<LmiBlock> blocks = {{1, {{0, Eigen::MatrixXd::Ones(1, 1)}}}, {1, {{1, Eigen::MatrixXd::Ones(1, 1)}}}};
    const BarrierResult r = minimise_with_lmis(Q, c, blocks, Eigen::VectorXd::Constant(2, 0.5));
    EXPECT_FALSE(r.converged);
    // The same problem without the NaN: x = c (the minimum of x^T x - 2 c^T x, inside x > 0).
    Q(0, 1) = Q(1, 0) = 0.0;
    const BarrierResult ok = minimise_with_lmis(Q, c, blocks, Eigen::VectorXd::Constant(2, 0.5));
    EXPECT_TRUE(ok.converged);
    EXPECT_NEAR(ok.x[0], 1.0, 1e-5);
    EXPECT_NEAR(ok.x[1], 1.0, 1e-5);
}

TEST(PhysicalLeastSquares, MismatchedSizesAreRefused) {
    const Problem pr = make_problem(Eigen::VectorXd::Ones(14), 1);
    EXPECT_THROW(solve_physical(pr.factor, 1.0, pr.regrouping, {"XX1"}, pr.unconstrained, {}), std::invalid_argument);
    EXPECT_THROW(PhysicalParametrization({"XX1", "XY1", "MX1"}, PhysicalConstraint::Full), std::invalid_argument);
}

}  // namespace
