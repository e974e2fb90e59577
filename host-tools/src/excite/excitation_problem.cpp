// SPDX-License-Identifier: MIT
#include "excite/excitation_problem.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "excite/periodic_lowpass.hpp"

namespace jacobid::excite {
namespace {

// The Kreisselmeier-Steinhauser aggregate of `terms` (a smooth upper bound of their maximum); when `weights` is
// not null, its derivative in each term there (the softmax weights).
double ks_aggregate(const std::vector<double>& terms, double rho, std::vector<double>* weights) {
    const double top = *std::max_element(terms.begin(), terms.end());
    double sum = 0.0;
    if (weights) {
        // Each exponential once (the sum's terms are the weights' numerators): the exponentials were 5 % of an evaluation's instructions.
        weights->resize(terms.size());
        for (std::size_t t = 0; t < terms.size(); ++t) sum += (*weights)[t] = std::exp(rho * (terms[t] - top));
        for (double& w : *weights) w /= sum;
    } else {
        for (const double t : terms) sum += std::exp(rho * (t - top));
    }
    return top + std::log(sum) / rho;
}

// Whether a kind limits |value| (terms of both signs) rather than the excursion toward one bound.
bool two_sided(LimitKind k) { return k != LimitKind::Upper && k != LimitKind::Lower; }
// The position kinds' excursion toward their bound: +1 upper, -1 lower (and +1 for the others).
double side(LimitKind k) { return k == LimitKind::Lower ? -1.0 : 1.0; }

}  // namespace

const char* to_string(LimitKind k) {
    switch (k) {
        case LimitKind::Upper: return "upper position";
        case LimitKind::Lower: return "lower position";
        case LimitKind::Velocity: return "velocity";
        case LimitKind::Acceleration: return "acceleration";
        case LimitKind::Torque: return "torque";
    }
    return "?";
}

ExcitationProblem::ExcitationProblem(const robot::RobotModel& model, Eigen::VectorXd parameters, FourierBasis basis, Eigen::VectorXd pose,
                                     std::vector<JointLimits> limits, ProblemSettings settings)
    : model_(model), x_(std::move(parameters)), basis_(std::move(basis)), pose_(std::move(pose)), limits_(std::move(limits)), settings_(settings) {
    joints_ = model.joint_count();
    columns_ = model.parameter_count();
    if (x_.size() != columns_ || pose_.size() != joints_ || static_cast<int>(limits_.size()) != joints_) {
        throw std::invalid_argument("ExcitationProblem: parameters, pose or limits do not match the model");
    }
    InformationModel& info = settings_.information;
    if (info.noise_std.size() == 0) info.noise_std = Eigen::VectorXd::Ones(joints_);
    // The parameters designed for: the base parameters, or the projection's columns (InformationModel::projection).
    if (info.projection.size() > 0 && info.projection.rows() != columns_) {
        throw std::invalid_argument("ExcitationProblem: the projection needs one row per base parameter");
    }
    const Eigen::Index designed = info.projection.size() > 0 ? info.projection.cols() : columns_;
    if (info.scale.size() == 0) info.scale = Eigen::VectorXd::Ones(designed);
    if (info.noise_std.size() != joints_ || info.scale.size() != designed || !(info.noise_std.minCoeff() > 0.0) || !(info.scale.minCoeff() > 0.0)) {
        throw std::invalid_argument("ExcitationProblem: the noise (one per joint) and prior scales (one per parameter) must be > 0");
    }
    const double highest = basis_.harmonics() * basis_.base_frequency();
    // Automatic: 20 samples per period of the highest harmonic (about what identify keeps: F_p at 5 x the motion
    // bandwidth, 4 samples per F_p period), at least 100; the information criteria sum the information over the
    // period, so they take twice that and at least 400, so that the sum is the integral identify's rows hold.
    const int identify_like = static_cast<int>(std::ceil(20.0 * highest * basis_.period()));
    samples_ = settings_.samples > 0                               ? settings_.samples
               : is_information_criterion(settings_.criterion) ? std::max(400, 2 * identify_like)
                                                                : std::max(100, identify_like);
    psi_.resize(basis_.size(), samples_), dpsi_.resize(basis_.size(), samples_), ddpsi_.resize(basis_.size(), samples_);
    for (int i = 0; i < samples_; ++i) {
        basis_.evaluate(basis_.period() * i / samples_, psi_.col(i), dpsi_.col(i), ddpsi_.col(i));
    }
    bases_.resize(basis_.size(), 3 * samples_);
    bases_ << psi_, dpsi_, ddpsi_;
    W_.resize(static_cast<Eigen::Index>(samples_) * joints_, columns_);
    derivatives_ = make_regressor_derivatives(model_, settings_.derivatives);
}

ExcitationProblem::ExcitationProblem(const ExcitationProblem& o)
    : model_(o.model_), x_(o.x_), basis_(o.basis_), pose_(o.pose_), limits_(o.limits_), settings_(o.settings_), joints_(o.joints_), columns_(o.columns_),
      samples_(o.samples_), psi_(o.psi_), dpsi_(o.dpsi_), ddpsi_(o.ddpsi_), bases_(o.bases_), W_(o.W_),
      derivatives_(make_regressor_derivatives(o.model_, o.derivatives_->route())), workspace_(o.workspace_) {}

void ExcitationProblem::set_decimation_cutoff(double cutoff_hz) {
    Eigen::MatrixXd& F = settings_.information.time_filter;
    if (cutoff_hz > 0.0) F = periodic_lowpass(samples_, basis_.period(), cutoff_hz);
    else F.resize(0, 0);
    derivatives_for_.resize(0);
}

void ExcitationProblem::use_derivative_route(DerivativeRoute route) {
    derivatives_ = make_regressor_derivatives(model_, route);
    derivatives_for_.resize(0);
}

bool ExcitationProblem::torque_limited() const {
    return std::any_of(limits_.begin(), limits_.end(), [](const JointLimits& l) { return std::isfinite(l.torque); });
}

void ExcitationProblem::set_limits(std::vector<JointLimits> limits) {
    if (static_cast<int>(limits.size()) != joints_) throw std::invalid_argument("ExcitationProblem::set_limits: one limit per joint");
    limits_ = std::move(limits);
    dtau_ready_ = false;  // the samples whose torque derivatives count depend on the limits (select_torque_samples)
}

void ExcitationProblem::set_workspace(std::optional<Workspace> workspace) {
    if (workspace && workspace->frame.joints() != joints_) throw std::invalid_argument("ExcitationProblem::set_workspace: the frame's chain does not match the model");
    workspace_ = std::move(workspace);
    prepared_for_.resize(0);  // the points are prepared with the rest
}

void ExcitationProblem::set_workspace_box(const WorkspaceBox& box) {
    if (!workspace_) throw std::invalid_argument("ExcitationProblem::set_workspace_box: no workspace");
    workspace_->box = box;
}

double ExcitationProblem::limit(int joint, LimitKind kind) const {
    const JointLimits& l = limits_[static_cast<std::size_t>(joint)];
    switch (kind) {
        case LimitKind::Upper: return l.upper - pose_[joint];
        case LimitKind::Lower: return pose_[joint] - l.lower;
        case LimitKind::Velocity: return l.velocity;
        case LimitKind::Acceleration: return l.acceleration;
        case LimitKind::Torque: return l.torque;
    }
    return 0.0;
}

FourierTrajectory ExcitationProblem::trajectory(const Eigen::VectorXd& c) const {
    return {basis_, pose_, Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(c.data(), joints_, basis_.size())};
}

void ExcitationProblem::prepare(const Eigen::VectorXd& c) {
    if (prepared_for_.size() == c.size() && prepared_for_ == c) return;
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> C(c.data(), joints_, basis_.size());
    q_ = (C * psi_).colwise() + pose_;
    qd_ = C * dpsi_;
    qdd_ = C * ddpsi_;
    tau_.resize(joints_, samples_);
    Eigen::MatrixXd Y(joints_, columns_);
    for (int i = 0; i < samples_; ++i) {
        const Eigen::VectorXd q = q_.col(i), qd = qd_.col(i), qdd = qdd_.col(i);
        model_.regressor(q.data(), qd.data(), qdd.data(), Y);
        W_.middleRows(static_cast<Eigen::Index>(i) * joints_, joints_) = Y;
        tau_.col(i) = Y * x_;
    }
    if (workspace_) {
        points_.resize(3, samples_);
        point_jacobians_.resize(static_cast<std::size_t>(samples_));
        for (int i = 0; i < samples_; ++i) points_.col(i) = workspace_->frame.point(q_.col(i), &point_jacobians_[static_cast<std::size_t>(i)]);
    }
    prepared_for_ = c;
}

double ExcitationProblem::limit_aggregate(int joint, LimitKind kind, Eigen::VectorXd* net) {
    const double room = limit(joint, kind), sign = side(kind);
    const bool both = two_sided(kind);
    terms_.clear();
    for (int i = 0; i < samples_; ++i) {
        double value = 0.0;
        switch (kind) {
            case LimitKind::Upper:
            case LimitKind::Lower: value = sign * (q_(joint, i) - pose_[joint]); break;
            case LimitKind::Velocity: value = qd_(joint, i); break;
            case LimitKind::Acceleration: value = qdd_(joint, i); break;
            case LimitKind::Torque: value = tau_(joint, i); break;
        }
        terms_.push_back(value / room - 1.0);
        if (both) terms_.push_back(-value / room - 1.0);
    }
    const double ks = ks_aggregate(terms_, settings_.ks_rho, net ? &weights_ : nullptr);
    if (net) {
        // d KS / d value: the sample's net weight (w+ - w-) over the limit.
        net->resize(samples_);
        for (int i = 0; i < samples_; ++i) {
            const auto t = static_cast<std::size_t>(i);
            (*net)[i] = (both ? weights_[2 * t] - weights_[2 * t + 1] : weights_[t]) / room;
        }
    }
    return ks;
}

// A sample's torque derivatives enter joint j's torque row only times its net KS weight there, and a design's
// torques reach their limits at a few peaks: the weights exp(rho (t_i - t_max)) of the other samples fall below
// 1e-14 once their torque is 0.16 of the limit below the peak's (rho = 200). A sample is swept when some joint's
// |net weight| is at least negligible_torque_weight / samples of that joint's largest; the samples left out then
// weigh together less than negligible_torque_weight (default eps = 2.2e-16) times the largest weight, so that what
// they would add to an entry of the row, at most eps max|net| max_i |dtau_i psi_i|, is one rounding unit of the
// peak's own term max|net| |dtau_peak psi_peak| times the ratio of the largest torque derivative to the peak's: the
// rounding of the kept sum itself.
void ExcitationProblem::select_torque_samples() {
    torque_swept_.setConstant(samples_, false);
    torque_ks_.resize(joints_);
    torque_net_.resize(samples_, joints_);
    const double share = settings_.negligible_torque_weight / samples_;
    for (int j = 0; j < joints_; ++j) {
        if (!std::isfinite(limit(j, LimitKind::Torque))) continue;
        torque_ks_[j] = limit_aggregate(j, LimitKind::Torque, &net_);
        torque_net_.col(j) = net_;
        const double floor = share * net_.cwiseAbs().maxCoeff();
        torque_swept_ = torque_swept_ || (net_.array().abs() >= floor);
    }
}

void ExcitationProblem::prepare_derivatives(const Eigen::VectorXd& c) {
    prepare(c);
    const bool torque = torque_limited();
    if (derivatives_for_.size() == c.size() && derivatives_for_ == c && (dtau_ready_ || !torque)) return;
    value_ = evaluate_criterion(settings_.criterion, W_, joints_, settings_.information, &GW_);
    const int n = joints_;
    dphi_.resize(samples_, 3 * n);
    select_torque_samples();
    // The samples not swept keep zero rows (not stale ones): the torque rows multiply them by their weights.
    if (torque) dtau_.setZero(3 * static_cast<Eigen::Index>(samples_), n * n);
    Eigen::VectorXd dphi;
    for (int i = 0; i < samples_; ++i) {
        const bool swept = torque_swept_[i];
        derivatives_->evaluate(q_.col(i).data(), qd_.col(i).data(), qdd_.col(i).data(), GW_.middleRows(static_cast<Eigen::Index>(i) * n, n), x_, dphi,
                               swept ? &sample_dtau_ : nullptr);
        dphi_.row(i) = dphi.transpose();
        if (!swept) continue;
        for (int z = 0; z < 3; ++z) {  // q, qd, qdd
            for (int j = 0; j < n; ++j) {
                dtau_.row(static_cast<Eigen::Index>(z) * samples_ + i).segment(static_cast<Eigen::Index>(j) * n, n) = sample_dtau_.row(j).segment(z * n, n);
            }
        }
    }
    derivatives_for_ = c;
    dtau_ready_ = torque;
}

double ExcitationProblem::criterion(const Eigen::VectorXd& c, Eigen::VectorXd* gradient) {
    if (!gradient) {
        prepare(c);
        return evaluate_criterion(settings_.criterion, W_, joints_, settings_.information, nullptr);
    }
    prepare_derivatives(c);
    // Joint a's coefficients (segment a, column a of G) get sum_i dphi/dq_a psi_i + dphi/dqd_a dpsi_i + dphi/dqdd_a ddpsi_i.
    gradient->resize(variables());
    Eigen::Map<Eigen::MatrixXd> G(gradient->data(), basis_.size(), joints_);
    G.noalias() = psi_ * dphi_.leftCols(joints_);
    G.noalias() += dpsi_ * dphi_.middleCols(joints_, joints_);
    G.noalias() += ddpsi_ * dphi_.rightCols(joints_);
    return value_;
}

double ExcitationProblem::condition_number(const Eigen::VectorXd& c) {
    prepare(c);
    return std::exp(evaluate_criterion(Criterion::Cond, W_, joints_, settings_.information, nullptr));  // log cond
}

Eigen::VectorXd ExcitationProblem::constraint_values(const Eigen::VectorXd& c, Eigen::MatrixXd* jacobian) {
    if (jacobian) {
        prepare_derivatives(c);
    } else {
        prepare(c);
    }
    const int m = basis_.size();
    Eigen::VectorXd g(constraints());
    if (jacobian) jacobian->setZero(constraints(), variables());
    // One KS aggregate over (sample, sign) of sign * value / limit - 1. Its gradient: per sample, the weights' net
    // d KS / d value (w+ - w-) / limit times d value / dc, summed into `slope` (joint a's coefficients: segment a).
    Eigen::VectorXd slope(variables());
    auto segment = [&](int joint) { return slope.segment(static_cast<Eigen::Index>(joint) * m, m); };
    for (int j = 0; j < joints_; ++j) {
        for (int kind = 0; kind < kLimitKinds; ++kind) {
            const auto k = static_cast<LimitKind>(kind);
            const int row = j * kLimitKinds + kind;
            if (!std::isfinite(limit(j, k))) {
                g[row] = -1.0;
                continue;
            }
            // With the Jacobian, the torque rows' aggregates and weights at c are select_torque_samples' (their exponentials once).
            const bool selected = jacobian && k == LimitKind::Torque;
            g[row] = selected ? torque_ks_[j] : limit_aggregate(j, k, jacobian ? &net_ : nullptr);
            if (!jacobian) continue;
            if (selected) net_ = torque_net_.col(j);
            slope.setZero();
            switch (k) {
                case LimitKind::Upper:
                case LimitKind::Lower: segment(j).noalias() = side(k) * (psi_ * net_); break;
                case LimitKind::Velocity: segment(j).noalias() = dpsi_ * net_; break;
                case LimitKind::Acceleration: segment(j).noalias() = ddpsi_ * net_; break;
                case LimitKind::Torque: {
                    // Every joint's coefficients (column a of the map: segment a) from joint j's columns of dtau_.
                    weighted_.resize(dtau_.rows(), joints_);
                    for (int z = 0; z < 3; ++z) {  // q, qd, qdd
                        weighted_.middleRows(static_cast<Eigen::Index>(z) * samples_, samples_).noalias() =
                            net_.asDiagonal() * dtau_.block(static_cast<Eigen::Index>(z) * samples_, static_cast<Eigen::Index>(j) * joints_, samples_, joints_);
                    }
                    Eigen::Map<Eigen::MatrixXd>(slope.data(), m, joints_).noalias() = bases_ * weighted_;
                    break;
                }
            }
            jacobian->row(row) = slope.transpose();
        }
    }
    if (workspace_) {
        // Face f: the point's excursion from its start toward the face over the face's room, minus 1; its
        // slope J_v(a, k) psi / room in joint k's coefficients (q_k = pose_k + c_k psi).
        for (int f = 0; f < kBoxFaces; ++f) {
            const int axis = f / 2, row = workspace_row() + f;
            const double sign = f % 2 == 0 ? 1.0 : -1.0, room = face_room(workspace_->box, workspace_->start, f);
            terms_.clear();
            for (int i = 0; i < samples_; ++i) terms_.push_back(sign * (points_(axis, i) - workspace_->start[axis]) / room - 1.0);
            g[row] = ks_aggregate(terms_, settings_.ks_rho, jacobian ? &weights_ : nullptr);
            if (!jacobian) continue;
            slope.setZero();
            for (int i = 0; i < samples_; ++i) {
                const Eigen::Matrix3Xd& J = point_jacobians_[static_cast<std::size_t>(i)];
                const double w = weights_[static_cast<std::size_t>(i)] * sign / room;
                for (int k = 0; k < joints_; ++k) segment(k) += (w * J(axis, k)) * psi_.col(i);
            }
            jacobian->row(row) = slope.transpose();
        }
    }
    return g;
}

LimitCheck check_limits(const robot::RobotModel& model, const Eigen::VectorXd& parameters, const FourierTrajectory& trajectory,
                        const std::vector<JointLimits>& limits, double rate) {
    const int n = trajectory.joints();
    const auto count = static_cast<std::size_t>(std::llround(trajectory.basis.period() * rate));
    LimitCheck r;
    r.ratio.setZero(n, kLimitKinds);
    r.peak.setZero(n, kLimitKinds);
    r.peak.col(0) = trajectory.pose;
    r.peak.col(1) = trajectory.pose;
    Eigen::VectorXd q(n), qd(n), qdd(n);
    Eigen::MatrixXd Y(n, model.parameter_count());
    for (std::size_t i = 0; i <= count; ++i) {
        trajectory.evaluate(static_cast<double>(i) / rate, q, qd, qdd);
        model.regressor(q.data(), qd.data(), qdd.data(), Y);
        const Eigen::VectorXd tau = Y * parameters;
        for (int j = 0; j < n; ++j) {
            const JointLimits& l = limits[static_cast<std::size_t>(j)];
            const double pose = trajectory.pose[j];
            r.peak(j, 0) = std::max(r.peak(j, 0), q[j]);
            r.peak(j, 1) = std::min(r.peak(j, 1), q[j]);
            r.peak(j, 2) = std::max(r.peak(j, 2), std::abs(qd[j]));
            r.peak(j, 3) = std::max(r.peak(j, 3), std::abs(qdd[j]));
            r.peak(j, 4) = std::max(r.peak(j, 4), std::abs(tau[j]));
            const double ratios[kLimitKinds] = {(q[j] - pose) / (l.upper - pose), (pose - q[j]) / (pose - l.lower), std::abs(qd[j]) / l.velocity,
                                                std::abs(qdd[j]) / l.acceleration, std::abs(tau[j]) / l.torque};
            for (int k = 0; k < kLimitKinds; ++k) {
                if (ratios[k] > r.ratio(j, k)) r.ratio(j, k) = ratios[k];
                if (ratios[k] > r.worst) r.worst = ratios[k], r.worst_joint = j, r.worst_kind = static_cast<LimitKind>(k), r.worst_sample = i;
            }
        }
    }
    return r;
}

}  // namespace jacobid::excite
