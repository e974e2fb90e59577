// SPDX-License-Identifier: MIT
#include "robot/serial_robot_model.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "jacobid/robot/articulated_body.hpp"
#include "jacobid/robot/rnea_regressor.hpp"

namespace jacobid::robot {

class SerialRobotModel::Evaluator {
public:
    virtual ~Evaluator() = default;
    // Standard regressor (n x P) and, when base_columns is given, only those columns.
    virtual void evaluate(const double* q, const double* qd, const double* qdd, const std::vector<int>* base_columns,
                          Eigen::Ref<Eigen::MatrixXd> out) const = 0;
    // tau = W_standard X* with X*[base_columns[b]] = X[b], all other standard entries 0.
    virtual void torques(const double* q, const double* qd, const double* qdd, const std::vector<int>& base_columns, const Eigen::VectorXd& X,
                         double* tau) const = 0;
    // The articulated-body forward dynamics of the same standard vector X*.
    virtual std::unique_ptr<DirectForwardDynamics> articulated_body(const std::vector<int>& base_columns, const Eigen::VectorXd& X) const = 0;
    // Joint j's Coulomb sign function at velocity qd: its FC column's only non-zero entry, in row j.
    virtual double coulomb(int joint, double qd) const = 0;
};

namespace {

// The articulated-body algorithm of N joints on the standard parameters X*: the rigid bodies from the
// inertial and rotor columns, the friction columns (FV, FC, FOFF) subtracted from the motor torque first,
// exactly as they enter tau = W X* on the inverse-dynamics side.
template <int N>
class ArticulatedBodyRoute final : public DirectForwardDynamics {
public:
    using Parameters = typename RneaRegressor<N>::Parameters;
    ArticulatedBodyRoute(const RneaRegressor<N>& regressor, const Parameters& standard)
        : regressor_(regressor), body_(regressor.chain(), regressor.gravity()), standard_(standard) {
        body_.set_standard_parameters(regressor.layout(), standard);
    }

    bool accelerations(const double* q, const double* qd, const double* tau, double* qdd) override {
        const int n = regressor_.joint_count();
        const auto& layout = regressor_.layout();
        vq_.setZero(), vqd_.setZero(), vtau_.setZero();
        for (int j = 0; j < n; ++j) {
            vq_[j] = q[j], vqd_[j] = qd[j];
            double friction = standard_[layout.column(j, ParameterKind::FV)] * qd[j] +
                              standard_[layout.column(j, ParameterKind::FC)] * regressor_.coulomb(j)(qd[j]);
            const int offset = layout.column(j, ParameterKind::FOFF);
            if (offset >= 0) friction += standard_[offset];
            vtau_[j] = tau[j] - friction;
        }
        const ArticulatedBodyStatus status = body_.forward_dynamics(vq_, vqd_, vtau_, data_, vqdd_);
        if (status == ArticulatedBodyStatus::NonFiniteInput) {
            throw std::invalid_argument("robot forward dynamics: non-finite joint position, velocity or torque");
        }
        if (status != ArticulatedBodyStatus::Ok) return false;
        for (int j = 0; j < n; ++j) qdd[j] = vqdd_[j];
        return true;
    }

private:
    const RneaRegressor<N>& regressor_;  // owned by the model, which outlives its forward dynamics
    ArticulatedBody<N> body_;
    Parameters standard_;
    typename ArticulatedBody<N>::Data data_;
    typename ArticulatedBody<N>::Joints vq_, vqd_, vtau_, vqdd_;
};

// The joint count is a template parameter of the lib regressor: one instantiation per count, so that a
// 6-axis arm runs the 6 x 84 fixed-size code rather than a padded maximum.
template <int N>
class FixedEvaluator final : public SerialRobotModel::Evaluator {
public:
    explicit FixedEvaluator(const RneaRegressor<N>& regressor) : regressor_(regressor) {}

    void evaluate(const double* q, const double* qd, const double* qdd, const std::vector<int>* base_columns,
                  Eigen::Ref<Eigen::MatrixXd> out) const override {
        const int n = regressor_.joint_count();
        typename RneaRegressor<N>::Joints vq, vqd, vqdd;
        load(q, qd, qdd, vq, vqd, vqdd);
        typename RneaRegressor<N>::Regressor W;
        if (regressor_.regressor(vq, vqd, vqdd, W) != RegressorStatus::Ok) {
            throw std::invalid_argument("robot regressor: non-finite joint position, velocity or acceleration");
        }
        if (!base_columns) {
            out = W.topLeftCorner(n, regressor_.parameter_count());
            return;
        }
        for (std::size_t c = 0; c < base_columns->size(); ++c) out.col(static_cast<Eigen::Index>(c)) = W.col((*base_columns)[c]).head(n);
    }

    void torques(const double* q, const double* qd, const double* qdd, const std::vector<int>& base_columns, const Eigen::VectorXd& X,
                 double* tau) const override {
        typename RneaRegressor<N>::Joints vq, vqd, vqdd, vtau;
        load(q, qd, qdd, vq, vqd, vqdd);
        if (regressor_.inverse_dynamics(vq, vqd, vqdd, standard_vector(base_columns, X), vtau) != RegressorStatus::Ok) {
            throw std::invalid_argument("robot inverse dynamics: non-finite joint position, velocity or acceleration");
        }
        for (int j = 0; j < regressor_.joint_count(); ++j) tau[j] = vtau[j];
    }

    std::unique_ptr<DirectForwardDynamics> articulated_body(const std::vector<int>& base_columns, const Eigen::VectorXd& X) const override {
        return std::make_unique<ArticulatedBodyRoute<N>>(regressor_, standard_vector(base_columns, X));
    }

    double coulomb(int joint, double qd) const override { return regressor_.coulomb(joint)(qd); }

private:
    // X* with X*[base_columns[b]] = X[b], all other standard entries 0.
    static typename RneaRegressor<N>::Parameters standard_vector(const std::vector<int>& base_columns, const Eigen::VectorXd& X) {
        typename RneaRegressor<N>::Parameters standard = RneaRegressor<N>::Parameters::Zero();
        for (std::size_t b = 0; b < base_columns.size(); ++b) standard[base_columns[b]] = X[static_cast<Eigen::Index>(b)];
        return standard;
    }

    void load(const double* q, const double* qd, const double* qdd, typename RneaRegressor<N>::Joints& vq, typename RneaRegressor<N>::Joints& vqd,
              typename RneaRegressor<N>::Joints& vqdd) const {
        vq.setZero(), vqd.setZero(), vqdd.setZero();
        for (int j = 0; j < regressor_.joint_count(); ++j) vq[j] = q[j], vqd[j] = qd[j], vqdd[j] = qdd[j];
    }

    RneaRegressor<N> regressor_;
};

template <int N>
std::unique_ptr<SerialRobotModel::Evaluator> make_evaluator(const SerialRobotConfig& config) {
    if constexpr (N > kMaxSerialJoints) {
        throw std::invalid_argument(fmt::format("{} joints: at most {} are supported", config.joints.size(), kMaxSerialJoints));
    } else {
        if (static_cast<int>(config.joints.size()) == N) return std::make_unique<FixedEvaluator<N>>(make_rnea_regressor<N>(config));
        return make_evaluator<N + 1>(config);
    }
}

// Priority of the standard columns as base parameters: link by link (a later link's parameters regroup into
// earlier ones, as in Khalil's rules); within a link the inertia tensor without YY, the first moments and
// mass, then YY (so that XXR = XX - YY and ZZR = ZZ + YY), then the joint's rotor inertia and friction.
std::vector<int> base_priority(int joints, const StandardParameterOptions& options) {
    const StandardParameterLayout<kMaxSerialJoints> layout(joints, options);
    using K = ParameterKind;
    const K order[] = {K::XX, K::XY, K::XZ, K::YZ, K::ZZ, K::MX, K::MY, K::MZ, K::M, K::YY, K::IA, K::FV, K::FC, K::FOFF};
    std::vector<int> priority;
    for (int j = 0; j < joints; ++j) {
        for (K kind : order) {
            const int c = layout.column(j, kind);
            if (c >= 0) priority.push_back(c);
        }
    }
    return priority;
}

}  // namespace

std::vector<std::string> standard_parameter_names(int joints, const StandardParameterOptions& options) {
    const StandardParameterLayout<kMaxSerialJoints> layout(std::min(joints, kMaxSerialJoints), options);
    std::vector<std::string> names;
    for (int c = 0; c < layout.count(); ++c) {
        const StandardParameterId id = layout.id(c);
        names.push_back(fmt::format("{}{}", kind_name(id.kind), id.joint + 1));
    }
    return names;
}

SerialRobotModel::SerialRobotModel(SerialRobotConfig config, const BaseParameterSettings& base_settings) : config_(std::move(config)) {
    const int n = joint_count();
    if (n < 1) throw std::invalid_argument("a serial robot needs at least one joint");
    if (n > kMaxSerialJoints) throw std::invalid_argument(fmt::format("{} joints: at most {} are supported", n, kMaxSerialJoints));
    evaluator_ = make_evaluator<1>(config_);
    standard_names_ = standard_parameter_names(n, config_.options);
    std::vector<bool> prismatic;
    for (const auto& joint : config_.joints) prismatic.push_back(joint.type == JointType::Prismatic);
    base_ = compute_base_parameters(
        n, standard_names_, base_priority(n, config_.options), prismatic,
        [this](const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> W) { standard_regressor(q, qd, qdd, W); },
        base_settings);
    for (std::size_t b = 0; b < base_.base_columns.size(); ++b) {
        for (int j = 0; j < n; ++j) {
            if (standard_names_[static_cast<std::size_t>(base_.base_columns[b])] == fmt::format("FC{}", j + 1)) {
                coulomb_columns_.emplace_back(static_cast<int>(b), j);
            }
        }
    }
}

void SerialRobotModel::coulomb_columns(const double*, const double* qd, const double*, Eigen::Ref<Eigen::MatrixXd> D) const {
    for (const auto& [column, joint] : coulomb_columns_) {
        D.col(column).setZero();
        D(joint, column) = evaluator_->coulomb(joint, qd[joint]);
    }
}

SerialRobotModel::~SerialRobotModel() = default;

int SerialRobotModel::standard_index(const std::string& name) const {
    const auto it = std::find(standard_names_.begin(), standard_names_.end(), name);
    return it == standard_names_.end() ? -1 : static_cast<int>(it - standard_names_.begin());
}

void SerialRobotModel::standard_regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> W) const {
    evaluator_->evaluate(q, qd, qdd, nullptr, W);
}

void SerialRobotModel::regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const {
    evaluator_->evaluate(q, qd, qdd, &base_.base_columns, D);
}

Eigen::VectorXd SerialRobotModel::base_values(const Eigen::VectorXd& standard) const {
    Eigen::VectorXd base = base_.regrouping * standard;
    const Eigen::VectorXd magnitude = base_.regrouping.cwiseAbs() * standard.cwiseAbs();
    for (Eigen::Index b = 0; b < base.size(); ++b) {
        if (std::abs(base[b]) <= 1e-13 * magnitude[b]) base[b] = 0.0;
    }
    return base;
}

bool SerialRobotModel::inverse_dynamics(const double* q, const double* qd, const double* qdd, const Eigen::VectorXd& X, double* tau) const {
    evaluator_->torques(q, qd, qdd, base_.base_columns, X, tau);
    return true;
}

std::unique_ptr<DirectForwardDynamics> SerialRobotModel::articulated_body(const Eigen::VectorXd& X) const {
    return evaluator_->articulated_body(base_.base_columns, X);
}

}  // namespace jacobid::robot
