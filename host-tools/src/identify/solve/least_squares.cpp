// SPDX-License-Identifier: MIT
#include "identify/solve/least_squares.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.hpp"
#include "identify/solve/residual_correlation.hpp"
#include "identify/pipeline/running_qr.hpp"

namespace jacobid::identify {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Factor of [W_active Y] from an augmented factor of [W_all Y]: R^T R is the Gram matrix, so the columns
// of R that are kept give the same Gram matrix for the sub-problem; one more QR makes it triangular.
Eigen::MatrixXd select_columns(const Eigen::MatrixXd& r, const std::vector<int>& columns) {
    const Eigen::Index c = static_cast<Eigen::Index>(columns.size());
    Eigen::MatrixXd m(r.rows(), c + 1);
    for (Eigen::Index k = 0; k < c; ++k) m.col(k) = r.col(columns[static_cast<std::size_t>(k)]);
    m.col(c) = r.col(r.cols() - 1);
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(m);
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(c + 1, c + 1);
    const Eigen::Index k = std::min<Eigen::Index>(m.rows(), c + 1);
    out.topRows(k) = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
    return out;
}

Eigen::MatrixXd stack(const JointFactors& f, const std::vector<double>& scale, std::size_t& rows) {
    const Eigen::Index n = f.r.front().cols();
    RunningQr total(static_cast<int>(n));
    rows = 0;
    for (std::size_t j = 0; j < f.r.size(); ++j) {
        total.add_factor(f.r[j], f.rows[j], scale[j]);
        rows += f.rows[j];
    }
    return total.r();
}

// Joint-wise HAC sandwich of the kept columns `cols` (indices into the factors' columns) at solution x with
// joint scales `scale` (see StdMethod::JointHac). Fills the per-joint diagnostics of `s`; returns the
// covariance of x.
Eigen::MatrixXd joint_hac_covariance(const JointFactors& f, const std::vector<int>& cols, const std::vector<double>& x,
                                     const std::vector<double>& scale, LsSolution& s) {
    const Eigen::Index k = static_cast<Eigen::Index>(cols.size());
    const std::size_t joints = f.r.size();
    std::size_t rows = 0;
    for (auto r : f.rows) rows += r;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(k, k), b = Eigen::MatrixXd::Zero(k, k);
    s.joint_sigma.assign(joints, kNaN);
    s.joint_long_run_factors.assign(joints, 1.0);
    s.joint_lag1_correlation.assign(joints, kNaN);
    s.std_lags = f.lagged.size() == joints && joints > 0 ? static_cast<int>(f.lagged.front().size()) : 0;
    for (std::size_t j = 0; j < joints; ++j) {
        const Eigen::Index n = f.r[j].cols();
        Eigen::MatrixXd m(n, k);
        Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
        for (Eigen::Index i = 0; i < k; ++i) {
            m.col(i) = f.r[j].col(cols[static_cast<std::size_t>(i)]);
            u[cols[static_cast<std::size_t>(i)]] = x[static_cast<std::size_t>(i)];
        }
        u[n - 1] = -1.0;
        const double gamma0 = (f.r[j] * u).squaredNorm();
        // Degrees of freedom shared between the joints in proportion to their rows.
        const double dof = static_cast<double>(f.rows[j]) * (1.0 - static_cast<double>(k) / static_cast<double>(std::max<std::size_t>(rows, 1)));
        const double var = dof > 0.0 ? gamma0 / dof : 0.0;
        double factor = 1.0;
        if (s.std_lags > 0) {
            factor = long_run_variance_factor(f.lagged[j], u, gamma0);
            const auto rho = residual_autocorrelation(f.lagged[j], u, gamma0);
            if (!rho.empty()) s.joint_lag1_correlation[j] = rho.front();
        }
        s.joint_sigma[j] = std::sqrt(var);
        s.joint_long_run_factors[j] = factor;
        const Eigen::MatrixXd gram = m.transpose() * m;
        const double w2 = scale[j] * scale[j];
        a += w2 * gram;
        b += w2 * w2 * var * factor * gram;
    }
    const Eigen::MatrixXd ainv = a.ldlt().solve(Eigen::MatrixXd::Identity(k, k));
    return ainv * b * ainv;
}

}  // namespace

Eigen::MatrixXd stacked_factor(const JointFactors& factors, const std::vector<double>& scale) {
    std::size_t rows = 0;
    return stack(factors, scale, rows);
}

const char* to_string(StdMethod m) { return m == StdMethod::Pooled ? "pooled" : "joint-hac"; }

namespace {

// The rank analysis of W_active (its R, `w`): zero columns first, then the column-normalised matrix's SVD;
// each null direction is reported (Unidentifiable) and a maximal independent subset kept, the first `rank`
// pivots of a column-pivoted QR. Returns the kept positions in `active`, sorted.
std::vector<int> identifiable_subset(const Eigen::MatrixXd& w, const std::vector<int>& active, double rank_tolerance, LsSolution& s) {
    const Eigen::Index c = w.cols();
    Eigen::VectorXd norms = w.colwise().norm();
    const double max_norm = norms.size() ? norms.maxCoeff() : 0.0;
    std::vector<int> nonzero;  // positions in `active`
    for (Eigen::Index k = 0; k < c; ++k) {
        if (norms[k] > 1e-10 * max_norm && norms[k] > 0.0) {
            nonzero.push_back(static_cast<int>(k));
        } else {
            Unidentifiable u;
            u.parameters = {active[static_cast<std::size_t>(k)]};
            u.coefficients = {1.0};
            u.zero_column = true;
            s.unidentifiable.push_back(u);
        }
    }
    const Eigen::Index nz = static_cast<Eigen::Index>(nonzero.size());
    std::vector<int> keep;
    if (nz == 0) return keep;
    Eigen::MatrixXd scaled(c, nz);
    for (Eigen::Index k = 0; k < nz; ++k) scaled.col(k) = w.col(nonzero[static_cast<std::size_t>(k)]) / norms[nonzero[static_cast<std::size_t>(k)]];
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeFullV);
    const Eigen::VectorXd sv = svd.singularValues();
    int rank = 0;
    for (Eigen::Index k = 0; k < sv.size(); ++k) {
        if (sv[k] > rank_tolerance * sv[0]) ++rank;
    }
    s.rank = rank;
    for (Eigen::Index k = rank; k < nz; ++k) {
        const Eigen::VectorXd v = svd.matrixV().col(k);
        Eigen::VectorXd a(nz);
        for (Eigen::Index i = 0; i < nz; ++i) a[i] = v[i] / norms[nonzero[static_cast<std::size_t>(i)]];
        const double amax = a.cwiseAbs().maxCoeff();
        Unidentifiable u;
        for (Eigen::Index i = 0; i < nz; ++i) {
            if (std::abs(v[i]) > 0.05) {  // members of the null direction that matter
                u.parameters.push_back(active[static_cast<std::size_t>(nonzero[static_cast<std::size_t>(i)])]);
                u.coefficients.push_back(a[i] / amax);
            }
        }
        s.unidentifiable.push_back(u);
    }
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> pivoted(scaled);
    for (int k = 0; k < rank; ++k) keep.push_back(nonzero[static_cast<std::size_t>(pivoted.colsPermutation().indices()[k])]);
    std::sort(keep.begin(), keep.end());
    return keep;
}

// The least squares on the kept columns of a stacked factor [R | R y; 0 | rho]: x, R11^-1 and |rho|.
struct SubsetSolution {
    std::vector<double> x;
    Eigen::MatrixXd rinv;
    double residual = 0.0;
};

SubsetSolution solve_subset(const Eigen::MatrixXd& factor, const std::vector<int>& keep) {
    const Eigen::Index k = static_cast<Eigen::Index>(keep.size());
    const Eigen::MatrixXd sub = select_columns(factor, keep);
    const auto r11 = sub.topLeftCorner(k, k).triangularView<Eigen::Upper>();
    const Eigen::VectorXd sol = r11.solve(sub.col(k).head(k));
    return {std::vector<double>(sol.data(), sol.data() + k), r11.solve(Eigen::MatrixXd::Identity(k, k)), std::abs(sub(k, k))};
}

// ||R_j [x; -1]|| restricted to the kept columns (all other parameters are 0 in this model).
double joint_residual(const JointFactors& factors, std::size_t j, const std::vector<int>& columns, const std::vector<double>& x) {
    Eigen::VectorXd v = -factors.r[j].col(factors.r[j].cols() - 1);
    for (std::size_t i = 0; i < columns.size(); ++i) v += factors.r[j].col(columns[i]) * x[i];
    return v.norm();
}

// Gautier: weight joint j by 1 / sigma_j, sigma_j^2 = ||rho_j||^2 / (r_j - c), from the OLS residuals (or the
// known noise, SolveOptions::joint_noise).
std::vector<double> joint_weights(const JointFactors& factors, const std::vector<int>& columns, const std::vector<double>& x, const SolveOptions& options) {
    std::vector<double> scale(factors.r.size(), 1.0);
    for (std::size_t j = 0; j < scale.size(); ++j) {
        const double dof = static_cast<double>(factors.rows[j]) - static_cast<double>(columns.size());
        const double sigma = j < options.joint_noise.size() ? options.joint_noise[j] : dof > 0 ? joint_residual(factors, j, columns, x) / std::sqrt(dof) : 0.0;
        scale[j] = sigma > 0.0 ? 1.0 / sigma : 1.0;
    }
    return scale;
}

// The solution's covariance, std and %sigma_r for the kept parameters (`columns`: their model indices):
// joint-hac (a sandwich over the joints' long-run variances) or pooled, C = sigma^2 R^-1 R^-T.
void fill_statistics(const JointFactors& factors, const std::vector<int>& columns, const SubsetSolution& solved, const SolveOptions& options,
                     LsSolution& s) {
    const Eigen::Index k = static_cast<Eigen::Index>(columns.size());
    const Eigen::Index all = static_cast<Eigen::Index>(s.names.size());
    s.std_method = options.std_method;
    Eigen::MatrixXd hac;
    if (options.std_method == StdMethod::JointHac && k > 0) hac = joint_hac_covariance(factors, columns, solved.x, s.joint_weights, s);
    const Eigen::MatrixXd covariance = hac.size()  ? hac
                                       : k > 0     ? Eigen::MatrixXd(s.sigma_rho * s.sigma_rho * solved.rinv * solved.rinv.transpose())
                                                   : Eigen::MatrixXd();
    s.covariance = Eigen::MatrixXd::Constant(all, all, kNaN);
    for (Eigen::Index i = 0; i < k; ++i) {
        for (Eigen::Index l = 0; l < k; ++l) s.covariance(columns[static_cast<std::size_t>(i)], columns[static_cast<std::size_t>(l)]) = covariance(i, l);
    }
    for (Eigen::Index i = 0; i < k; ++i) {
        const auto p = static_cast<Eigen::Index>(columns[static_cast<std::size_t>(i)]);
        const double x = solved.x[static_cast<std::size_t>(i)];
        s.identified[static_cast<std::size_t>(p)] = true;
        s.x[p] = x;
        const double sd = hac.size() ? std::sqrt(std::max(hac(i, i), 0.0)) : s.sigma_rho * solved.rinv.row(i).norm();
        s.std_dev[p] = sd;
        s.rel_std_percent[p] = 100.0 * sd / std::abs(x);
    }
}

}  // namespace

LsSolution solve_least_squares(const JointFactors& factors, const std::vector<std::string>& names, const SolveOptions& options) {
    const int all = static_cast<int>(names.size());
    const std::size_t joints = factors.r.size();
    // Here, where every command that fits (identify, montecarlo, payload, drive gains) passes: a short list would
    // weigh the joints past its end by their residuals and the others by the noise.
    if (!options.joint_noise.empty() && options.joint_noise.size() != joints) {
        throw InputError(fmt::format("--joint-noise needs one value per joint: {} given for {} joints", options.joint_noise.size(), joints));
    }
    LsSolution s;
    s.names = names;
    s.x = Eigen::VectorXd::Constant(all, kNaN);
    s.std_dev = Eigen::VectorXd::Constant(all, kNaN);
    s.rel_std_percent = Eigen::VectorXd::Constant(all, kNaN);
    s.identified.assign(static_cast<std::size_t>(all), false);
    s.removed.assign(static_cast<std::size_t>(all), false);
    s.joint_weights.assign(joints, 1.0);
    s.joint_residual_rms.assign(joints, kNaN);

    std::vector<int> active;
    for (int p = 0; p < all; ++p) {
        if (options.active.empty() || options.active[static_cast<std::size_t>(p)]) active.push_back(p);
        else s.removed[static_cast<std::size_t>(p)] = true;
    }
    std::size_t rows = 0;
    const Eigen::MatrixXd total = select_columns(stack(factors, s.joint_weights, rows), active);
    s.equations = rows;
    const Eigen::Index c = static_cast<Eigen::Index>(active.size());
    const std::vector<int> keep = identifiable_subset(total.topLeftCorner(c, c), active, options.rank_tolerance, s);  // positions in `active`
    std::vector<int> columns;  // the kept parameters' indices in the model
    for (int i : keep) columns.push_back(active[static_cast<std::size_t>(i)]);

    SubsetSolution solved;
    if (!keep.empty()) solved = solve_subset(total, keep);
    if (options.weighted && !keep.empty()) {
        s.joint_weights = joint_weights(factors, columns, solved.x, options);
        s.weighted = true;
        std::size_t unused = 0;
        solved = solve_subset(select_columns(stack(factors, s.joint_weights, unused), active), keep);
    }
    const Eigen::Index k = static_cast<Eigen::Index>(keep.size());
    s.identified_count = static_cast<int>(k);
    // sigma_rho from the residual of the problem actually solved (weighted or not); the norms reported
    // are the unweighted ones, comparable between OLS and WLS.
    const double dof = static_cast<double>(rows) - static_cast<double>(k);
    s.sigma_rho = dof > 0 ? solved.residual / std::sqrt(dof) : kNaN;
    double y2 = 0.0, e2 = 0.0;
    for (std::size_t j = 0; j < joints; ++j) {
        const double yj = factors.r[j].col(factors.r[j].cols() - 1).norm();
        y2 += yj * yj;
        const double ej = keep.empty() ? yj : joint_residual(factors, j, columns, solved.x);
        e2 += ej * ej;
    }
    s.y_norm = std::sqrt(y2);
    s.residual_norm = std::sqrt(e2);
    s.relative_error_norm = s.y_norm > 0 ? s.residual_norm / s.y_norm : kNaN;
    fill_statistics(factors, columns, solved, options, s);
    if (k > 0) {
        const Eigen::MatrixXd wk = select_columns(total, keep).topLeftCorner(k, k);
        const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(wk).singularValues();
        s.cond = sv[sv.size() - 1] > 0 ? sv[0] / sv[sv.size() - 1] : std::numeric_limits<double>::infinity();
    }
    for (std::size_t j = 0; j < joints; ++j) {
        s.joint_residual_rms[j] = factors.rows[j] > 0 && !keep.empty() ? joint_residual(factors, j, columns, solved.x) / std::sqrt(static_cast<double>(factors.rows[j])) : kNaN;
    }
    return s;
}

EssentialResult essential_parameters(const JointFactors& factors, const std::vector<std::string>& names, double threshold_percent,
                                     const SolveOptions& options) {
    EssentialResult result;
    SolveOptions o = options;
    if (o.active.empty()) o.active.assign(names.size(), true);
    LsSolution s = solve_least_squares(factors, names, o);
    result.steps.push_back({"", 0.0, s.relative_error_norm, s.identified_count});
    while (s.identified_count > 1) {
        int worst = -1;
        double worst_value = threshold_percent;
        for (Eigen::Index p = 0; p < s.x.size(); ++p) {
            if (s.identified[static_cast<std::size_t>(p)] && s.rel_std_percent[p] > worst_value) {
                worst = static_cast<int>(p);
                worst_value = s.rel_std_percent[p];
            }
        }
        if (worst < 0) break;
        o.active[static_cast<std::size_t>(worst)] = false;
        s = solve_least_squares(factors, names, o);
        result.steps.push_back({names[static_cast<std::size_t>(worst)], worst_value, s.relative_error_norm, s.identified_count});
    }
    result.solution = s;
    return result;
}

void require_finite_solution(const LsSolution& solution, const std::string& source) {
    for (Eigen::Index c = 0; c < solution.x.size(); ++c) {
        const auto i = static_cast<std::size_t>(c);
        if (!solution.identified[i] || std::isfinite(solution.x[c])) continue;
        throw InputError(fmt::format("{}: the identified {} is not finite (values in the log too large for the least squares; look for an outlier)",
                                     source, solution.names[i]));
    }
}

}  // namespace jacobid::identify
