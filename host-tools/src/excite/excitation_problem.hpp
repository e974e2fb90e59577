// SPDX-License-Identifier: MIT
#pragma once
// The optimization problem of `jacobid excite` (docs/excite.md): the coefficients c of a Fourier
// trajectory (fourier_trajectory.hpp) that minimise a criterion of the base regressor W(c) stacked over the
// samples of one period, subject to the joints' limits.
//
//  - Criterion: one of information_criterion.hpp's (d-optimal, a-relative, e-relative on the noise-weighted
//    information matrix; cond, logdet of the column-scaled W), with its exact gradient in W chained to c
//    through dW/dc = dY/dq psi + dY/dqd psi' + dY/dqdd psi'': per sample i the 3n derivatives of <dF/dW_i, Y> in
//    (q, qd, qdd) (regressor_derivatives.hpp), times the basis.
//  - Constraints, per joint and kind (upper and lower position, |velocity|, |acceleration|, |torque|): the
//    normalized values g = value / limit - 1 over the samples, aggregated by the Kreisselmeier-Steinhauser
//    function KS(g) = max g + log(sum exp(rho (g - max g))) / rho >= max g (smooth, conservative); the
//    torque is Y(q, qd, qdd) x with x the description's parameters (the model's torque). The limits are also
//    checked at every control sample afterwards (check_limits).
//  - Optional workspace box (workspace_box.hpp): per face of the box, the normalized excursion of a frame's
//    point from its start toward the face, aggregated the same way; its gradient is exact:
//    dp/dc = J_v(q) dq/dc, J_v the point's translational Jacobian (frame_kinematics.hpp).
#include <Eigen/Core>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "excite/fourier_trajectory.hpp"
#include "excite/information_criterion.hpp"
#include "excite/regressor_derivatives.hpp"
#include "excite/workspace_box.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::excite {

struct JointLimits {
    double lower = -std::numeric_limits<double>::infinity(), upper = std::numeric_limits<double>::infinity();  // rad
    double velocity = std::numeric_limits<double>::infinity();      // rad/s
    double acceleration = std::numeric_limits<double>::infinity();  // rad/s^2
    double torque = std::numeric_limits<double>::infinity();        // N.m
};

enum class LimitKind { Upper, Lower, Velocity, Acceleration, Torque };
const char* to_string(LimitKind k);
constexpr int kLimitKinds = 5;

struct ProblemSettings {
    Criterion criterion = Criterion::DOptimal;
    InformationModel information;  // noise, prior scales, sample weight (information criteria only)
    int samples = 0;       // per period for the criterion and constraints; 0: 20 per period of the highest harmonic (>= 100; information criteria: 40, >= 400)
    double ks_rho = 200.0; // sharpness of the KS aggregate (dimensionless g): over-estimate <= log(2 N) / rho
    DerivativeRoute derivatives = DerivativeRoute::Adjoint;  // the regressor's derivatives (regressor_derivatives.hpp)
    // The torque constraints' Jacobian weighs each sample's torque derivatives by its KS weight, and at a design most
    // weights are far below rounding: the torque's derivatives are computed only at the samples where some joint's
    // weight is at least this share of that joint's largest divided by the samples, so that the weights left out
    // sum to at most this share of the largest (the default: one rounding unit); 0: at every sample.
    double negligible_torque_weight = std::numeric_limits<double>::epsilon();
};

class ExcitationProblem {
public:
    // model: the identification model (its columns are W's); parameters: its values (for the torque);
    // limits: one per joint. std::invalid_argument for sizes that do not match.
    ExcitationProblem(const robot::RobotModel& model, Eigen::VectorXd parameters, FourierBasis basis, Eigen::VectorXd pose,
                      std::vector<JointLimits> limits, ProblemSettings settings);
    ExcitationProblem(const ExcitationProblem& other);  // a copy for another thread (its own caches, the same model)
    ExcitationProblem& operator=(const ExcitationProblem&) = delete;
    // The route of the regressor's derivatives (regressor_derivatives.hpp): the adjoint (the default), central
    // differences or automatic differentiation (the last two for comparison: the benchmark, the tests, --derivatives).
    void use_derivative_route(DerivativeRoute route);
    DerivativeRoute derivative_route() const { return derivatives_->route(); }

    int variables() const { return joints_ * basis_.size(); }
    int constraints() const { return joints_ * kLimitKinds + (workspace_ ? kBoxFaces : 0); }
    // The first constraint of the workspace box (its faces follow, face_name order), when there is one.
    int workspace_row() const { return joints_ * kLimitKinds; }
    int samples() const { return samples_; }
    const FourierBasis& basis() const { return basis_; }
    const Eigen::VectorXd& pose() const { return pose_; }
    Criterion criterion_kind() const { return settings_.criterion; }
    void set_criterion(Criterion criterion) {
        settings_.criterion = criterion;
        derivatives_for_.resize(0);
    }
    // The log samples each criterion sample stands for (InformationModel::sample_weight).
    void set_sample_weight(double weight) {
        settings_.information.sample_weight = weight;
        derivatives_for_.resize(0);
    }

    // The information criteria of the regressor filtered like identify's F_p at `cutoff_hz` (periodic_lowpass.hpp,
    // InformationModel::time_filter); 0: unfiltered (the default).
    void set_decimation_cutoff(double cutoff_hz);

    // c: joints x 2L coefficients, row-major flattened (joint 0's first). The criterion, its gradient when
    // `gradient` is not null.
    double criterion(const Eigen::VectorXd& c, Eigen::VectorXd* gradient);
    // The constraint values (<= 0 when met; constraint index j * kLimitKinds + kind), their Jacobian
    // (constraints x variables) when `jacobian` is not null. A kind whose limit is infinite gives -1. With a
    // workspace, rows workspace_row() + face.
    Eigen::VectorXd constraint_values(const Eigen::VectorXd& c, Eigen::MatrixXd* jacobian);
    // cond(W_s) at c (whatever the criterion).
    double condition_number(const Eigen::VectorXd& c);

    FourierTrajectory trajectory(const Eigen::VectorXd& c) const;
    // New limits for the constraints (the optimizer's tightening rounds); same joint count.
    void set_limits(std::vector<JointLimits> limits);
    // The workspace box constraint (none: no box); its start must be the point at pose().
    void set_workspace(std::optional<Workspace> workspace);
    const std::optional<Workspace>& workspace() const { return workspace_; }
    // A new box for the same point (the optimizer's margin and tightening rounds).
    void set_workspace_box(const WorkspaceBox& box);
    // Per sample, whether the last derivatives (criterion or constraints with a gradient) computed its torque
    // derivatives (ProblemSettings::negligible_torque_weight); none without a torque limit.
    const Eigen::Array<bool, Eigen::Dynamic, 1>& torque_swept() const { return torque_swept_; }

private:
    void prepare(const Eigen::VectorXd& c);              // per-sample states, regressors and torques at c (cached)
    void prepare_derivatives(const Eigen::VectorXd& c);  // and dF/dW, the criterion, per-sample dphi and (with a torque limit) dtau (cached)
    bool torque_limited() const;                         // whether a joint's torque limit is finite (the constraints need dtau)
    void select_torque_samples();                        // torque_swept_ from the torque constraints' KS weights at the prepared point
    double limit(int joint, LimitKind kind) const;
    // The KS aggregate of joint j's constraint of kind k at the prepared point; with `net`, its derivative in the
    // limited value (position excursion, velocity, acceleration or torque) at each sample.
    double limit_aggregate(int joint, LimitKind kind, Eigen::VectorXd* net);

    const robot::RobotModel& model_;
    Eigen::VectorXd x_;
    FourierBasis basis_;
    Eigen::VectorXd pose_;
    std::vector<JointLimits> limits_;
    ProblemSettings settings_;
    int joints_ = 0, columns_ = 0, samples_ = 0;
    // At every sample: basis values (size() x samples), q/qd/qdd (joints x samples), torque. bases_ = [psi_ dpsi_
    // ddpsi_] side by side (size() x 3 samples): a gradient in (q, qd, qdd) stacked the same way over the samples
    // goes to the coefficients in one product.
    Eigen::MatrixXd psi_, dpsi_, ddpsi_, bases_;
    Eigen::MatrixXd q_, qd_, qdd_, tau_;
    Eigen::MatrixXd W_;                 // (samples * joints) x columns
    std::unique_ptr<RegressorDerivatives> derivatives_;
    double value_ = 0.0;                // the criterion at derivatives_for_
    Eigen::MatrixXd GW_;                // dF/dW there (W_'s shape; kept so that its storage is reused)
    Eigen::MatrixXd dphi_;              // samples x 3 * joints: d<dF/dW_i, Y_i>/d(q, qd, qdd) (row i)
    // When torque_limited(): d tau_j / dz_(kind, a) at sample i in row kind * samples + i, column j * joints + a
    // (kind 0, 1, 2: q, qd, qdd), so that joint j's columns, each sample's rows scaled by its KS weight, times
    // bases_ are that torque constraint's Jacobian row; weighted_ holds them scaled.
    // Rows only at the samples in torque_swept_ (select_torque_samples); the others' are 0.
    Eigen::MatrixXd dtau_, weighted_;
    Eigen::MatrixXd sample_dtau_;       // one sample's joints x 3 * joints (the derivatives' output, reused)
    Eigen::Array<bool, Eigen::Dynamic, 1> torque_swept_;  // per sample: whether dtau_ has its rows
    // The torque constraints where dtau_ was computed (select_torque_samples): each aggregate (joints) and its net
    // KS weight at each sample (samples x joints), for constraint_values.
    Eigen::VectorXd torque_ks_;
    Eigen::MatrixXd torque_net_;
    Eigen::VectorXd derivatives_for_;
    bool dtau_ready_ = false;           // dtau_ holds derivatives_for_'s, for the current limits
    // The KS aggregates' terms, their weights and each sample's net weight (kept: no allocation per evaluation).
    std::vector<double> terms_, weights_;
    Eigen::VectorXd net_;
    std::optional<Workspace> workspace_;
    Eigen::Matrix3Xd points_;                      // the workspace point at every sample (base frame)
    std::vector<Eigen::Matrix3Xd> point_jacobians_;  // per sample, dp/dq (3 x joints)
    Eigen::VectorXd prepared_for_;
};

// Every control sample of one period (rate in Hz): peak |value| / limit per joint and kind, and the worst.
struct LimitCheck {
    Eigen::MatrixXd ratio;    // joints x kLimitKinds: peak value / limit (position: excursion past the pose toward the bound / room)
    Eigen::MatrixXd peak;     // joints x kLimitKinds: peak value (rad, rad/s, rad/s^2, N.m; position kinds: max q, min q)
    double worst = 0.0;       // largest ratio
    int worst_joint = 0;
    LimitKind worst_kind = LimitKind::Upper;
    std::size_t worst_sample = 0;
};
LimitCheck check_limits(const robot::RobotModel& model, const Eigen::VectorXd& parameters, const FourierTrajectory& trajectory,
                        const std::vector<JointLimits>& limits, double rate);

}  // namespace jacobid::excite
