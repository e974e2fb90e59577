// SPDX-License-Identifier: MIT
#include "excite/information_criterion.hpp"

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace jacobid::excite {
namespace {

// The smallest pivot of the unit-diagonal (column-equilibrated) Gram matrix's Cholesky factor that counts as
// full rank: below it the matrix is singular to rounding (pivot^2 ~ 1e-16).
constexpr double kPivot = 1e-8;

// A positive definite matrix factored after equilibration (unit diagonal), so that parameters of very
// different units do not fail the factorization: G = D^-1 Gs D^-1, Gs = L L^T.
struct Factored {
    Eigen::VectorXd d;  // 1 / sqrt(G_kk)
    Eigen::LLT<Eigen::MatrixXd> llt;
    bool ok = false;
    double log_det = 0.0;  // log det G

    explicit Factored(const Eigen::MatrixXd& G) {
        d = G.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
        llt.compute(d.asDiagonal() * G * d.asDiagonal());
        if (llt.info() != Eigen::Success || !G.diagonal().allFinite() || (G.diagonal().array() <= 0.0).any()) return;
        const Eigen::VectorXd pivots = llt.matrixLLT().diagonal();
        if (!(pivots.minCoeff() > kPivot)) return;
        ok = true;
        log_det = 2.0 * pivots.array().log().sum() - 2.0 * d.array().log().sum();
    }
    // G^-1 = D Gs^-1 D.
    Eigen::MatrixXd inverse() const {
        const Eigen::Index p = d.size();
        return d.asDiagonal() * llt.solve(Eigen::MatrixXd::Identity(p, p)) * d.asDiagonal();
    }
};

// The rows of joint j in W (every joints-th row from row j): a strided view, no copy.
template <typename Matrix>
auto joint_rows(Matrix& W, int joints, int j) {
    using Target = std::conditional_t<std::is_const_v<Matrix>, const Eigen::MatrixXd, Eigen::MatrixXd>;
    using Strides = Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>;
    return Eigen::Map<Target, 0, Strides>(W.data() + j, W.rows() / joints, W.cols(), Strides(W.outerStride(), joints));
}

double column_scaled_criterion(Criterion criterion, const Eigen::MatrixXd& W, Eigen::MatrixXd* dW) {
    // W_s = W S, S = diag(1 / ||w_k||).
    const Eigen::Index columns = W.cols();
    const Eigen::VectorXd s = W.colwise().norm().transpose().cwiseMax(1e-300).cwiseInverse();
    const Eigen::MatrixXd Ws = W * s.asDiagonal();
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Ws, dW ? Eigen::ComputeThinU | Eigen::ComputeThinV : 0);
    const Eigen::VectorXd& sigma = svd.singularValues();
    const Eigen::Index p = sigma.size();
    double value = 0.0;
    Eigen::MatrixXd G;  // dF/dW_s
    if (criterion == Criterion::Cond) {
        value = std::log(sigma[0]) - std::log(sigma[p - 1]);
        if (dW) {
            G = svd.matrixU().col(0) * svd.matrixV().col(0).transpose() / sigma[0] -
                svd.matrixU().col(p - 1) * svd.matrixV().col(p - 1).transpose() / sigma[p - 1];
        }
    } else {
        value = -2.0 * sigma.array().log().sum();
        if (dW) G = -2.0 * svd.matrixU() * sigma.cwiseInverse().asDiagonal() * svd.matrixV().transpose();
    }
    if (!std::isfinite(value)) value = kRankDeficient;
    if (!dW) return value;
    // W_s's columns are w_k s_k with s_k = 1 / ||w_k||, d s_k / d w_k = -w_k / ||w_k||^3.
    dW->resize(W.rows(), columns);
    for (Eigen::Index k = 0; k < columns; ++k) {
        dW->col(k) = G.col(k) * s[k] - (G.col(k).dot(W.col(k)) * s[k] * s[k] * s[k]) * W.col(k);
    }
    if (!dW->allFinite()) dW->setZero();
    return value;
}

}  // namespace

const char* to_string(Criterion c) {
    switch (c) {
        case Criterion::Cond: return "cond";
        case Criterion::LogDet: return "logdet";
        case Criterion::DOptimal: return "d-optimal";
        case Criterion::ARelative: return "a-relative";
        case Criterion::ERelative: return "e-relative";
        case Criterion::IOptimal: return "i-optimal";
    }
    return "?";
}

std::optional<Criterion> criterion_from_string(const std::string& name) {
    for (const Criterion c : {Criterion::Cond, Criterion::LogDet, Criterion::DOptimal, Criterion::ARelative, Criterion::ERelative, Criterion::IOptimal}) {
        if (name == to_string(c)) return c;
    }
    return std::nullopt;
}

bool is_information_criterion(Criterion c) { return c != Criterion::Cond && c != Criterion::LogDet; }

Eigen::MatrixXd information_matrix(const Eigen::MatrixXd& W, int joints, const Eigen::VectorXd& noise_std, double sample_weight) {
    // W's rows over their joint's sigma, into storage kept per thread: the optimizer asks for the same size at
    // every evaluation, and a fresh 1 MB matrix each time cost more in page faults than the product itself.
    thread_local Eigen::MatrixXd Wt;
    Wt.resize(W.rows(), W.cols());
    for (int j = 0; j < joints; ++j) joint_rows(Wt, joints, j) = joint_rows(W, joints, j) / noise_std[j];
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(W.cols(), W.cols());
    A.selfadjointView<Eigen::Lower>().rankUpdate(Wt.transpose(), sample_weight);
    return A.selfadjointView<Eigen::Lower>();
}

namespace {

// The criterion of W as it is (InformationModel::time_filter not applied).
double unfiltered_criterion(Criterion criterion, const Eigen::MatrixXd& W, int joints, const InformationModel& model, bool project, Eigen::MatrixXd* dW);

}  // namespace

double evaluate_criterion(Criterion criterion, const Eigen::MatrixXd& W, int joints, const InformationModel& model, Eigen::MatrixXd* dW) {
    const Eigen::MatrixXd& F = model.time_filter;
    if (F.size() == 0 || !is_information_criterion(criterion)) return unfiltered_criterion(criterion, W, joints, model, true, dW);
    if (F.rows() != W.rows() / joints || F.cols() != F.rows()) throw std::invalid_argument("evaluate_criterion: the time filter needs one row and column per sample");
    // Per-thread storage, reused: the optimizer asks for the same sizes at every evaluation.
    thread_local Eigen::MatrixXd Wf, dWf;
    Wf.resize(W.rows(), W.cols());
    for (int j = 0; j < joints; ++j) joint_rows(Wf, joints, j).noalias() = F * joint_rows(W, joints, j);
    const double value = unfiltered_criterion(criterion, Wf, joints, model, true, dW ? &dWf : nullptr);
    if (dW) {
        dW->resize(W.rows(), W.cols());
        for (int j = 0; j < joints; ++j) joint_rows(*dW, joints, j).noalias() = F * joint_rows(dWf, joints, j);  // F symmetric: F^T = F
    }
    return value;
}

namespace {

double unfiltered_criterion(Criterion criterion, const Eigen::MatrixXd& W, int joints, const InformationModel& model, bool project, Eigen::MatrixXd* dW) {
    if (project && model.projection.size() > 0) {
        // The criterion of V = W K (the parameters designed for), chained back: dF/dW = dF/dV K^T.
        thread_local Eigen::MatrixXd V, dV;
        V.noalias() = W * model.projection;
        const double value = unfiltered_criterion(criterion, V, joints, model, false, dW ? &dV : nullptr);
        if (dW) {
            dW->resize(W.rows(), W.cols());
            dW->noalias() = dV * model.projection.transpose();
        }
        return value;
    }
    if (!is_information_criterion(criterion)) return column_scaled_criterion(criterion, W, dW);
    const double gamma = model.sample_weight;
    const Factored A(information_matrix(W, joints, model.noise_std, gamma));
    if (!A.ok) {
        if (dW) dW->setZero(W.rows(), W.cols());
        return kRankDeficient;
    }
    const Eigen::MatrixXd C = A.inverse();  // the predicted covariance
    double value = 0.0;
    Eigen::MatrixXd inner;                  // dF/dW = -2 gamma S^-1 W inner
    if (criterion == Criterion::DOptimal) {
        value = -A.log_det;
        if (dW) inner = C;
    } else if (criterion == Criterion::IOptimal) {
        if (model.reference.rows() != C.rows() || model.reference.cols() != C.cols()) {
            throw std::invalid_argument("i-optimal: the reference information must have one row and column per base parameter");
        }
        const Eigen::MatrixXd MC = model.reference * C;
        const double trace = MC.trace();
        value = std::log(trace);
        if (dW) inner = C * MC / trace;  // C M C / trace(M C)
    } else {
        const Eigen::ArrayXd scale2 = model.scale.array().square();
        const Eigen::ArrayXd r = C.diagonal().array() / scale2;  // predicted relative variances
        Eigen::ArrayXd df_dr;
        if (criterion == Criterion::ARelative) {
            const double sum = r.sum();
            value = std::log(sum);
            df_dr = Eigen::ArrayXd::Constant(r.size(), 1.0 / sum);
        } else {
            const Eigen::ArrayXd lr = r.log();
            const double top = lr.maxCoeff();
            const Eigen::ArrayXd e = (kMaxSharpness * (lr - top)).exp();
            value = top + std::log(e.sum()) / kMaxSharpness;
            df_dr = e / e.sum() / r;
        }
        if (dW) inner = C * (df_dr / scale2).matrix().asDiagonal() * C;
    }
    if (dW) {
        // Into dW's own storage (the caller's, reused from call to call), then joint j's rows times -2 gamma / sigma_j^2.
        dW->resize(W.rows(), W.cols());
        dW->noalias() = W * inner;
        for (int j = 0; j < joints; ++j) joint_rows(*dW, joints, j) *= -2.0 * gamma / (model.noise_std[j] * model.noise_std[j]);
        if (!dW->allFinite()) dW->setZero();
    }
    return std::isfinite(value) ? value : kRankDeficient;
}

}  // namespace

Prediction predict(const Eigen::MatrixXd& information, const Eigen::VectorXd& scale, const Eigen::MatrixXd* reference) {
    Prediction p;
    const Eigen::Index n = information.rows();
    p.std_dev = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
    p.relative_std = p.std_dev;
    p.worst_relative_std = std::numeric_limits<double>::infinity();
    const Factored A(information);
    if (!A.ok) return p;
    p.identifiable = true;
    p.log_det = A.log_det;
    const Eigen::MatrixXd covariance = A.inverse();
    p.std_dev = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
    if (reference && reference->rows() == covariance.rows()) p.reference_rms = std::sqrt(std::max(0.0, (*reference * covariance).trace()));
    p.relative_std = p.std_dev.cwiseQuotient(scale);
    p.worst_relative_std = p.relative_std.maxCoeff(&p.worst);
    return p;
}

}  // namespace jacobid::excite
