// SPDX-License-Identifier: MIT
#include "robot/load_friction_model.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace jacobid::robot {
namespace {

bool is_friction_or_offset(const std::string& name) {
    return name.rfind("FV", 0) == 0 || name.rfind("FC", 0) == 0 || name.rfind("FOFF", 0) == 0 || name.rfind("FD", 0) == 0;
}

// Scratch of one gravity evaluation: tau = D(q, 0, 0) X_g.
struct GravityScratch {
    Eigen::MatrixXd D;
    std::vector<double> zero;
    Eigen::VectorXd tau;
    void fit(int joints, int parameters) {
        if (D.rows() != joints || D.cols() != parameters) D.resize(joints, parameters);
        if (zero.size() != static_cast<std::size_t>(joints)) zero.assign(static_cast<std::size_t>(joints), 0.0);
        if (tau.size() != joints) tau.resize(joints);
    }
};

// The reference gravity torques at q into tau (joint_count entries): the nominal model's own inverse
// dynamics where it has one, its regressor otherwise.
void gravity_torques(const RobotModel& nominal, const Eigen::VectorXd& parameters, const double* q, GravityScratch& s, double* tau) {
    s.fit(nominal.joint_count(), nominal.parameter_count());
    if (nominal.inverse_dynamics(q, s.zero.data(), s.zero.data(), parameters, tau)) return;
    nominal.regressor(q, s.zero.data(), s.zero.data(), s.D);
    s.tau.noalias() = s.D * parameters;
    std::copy(s.tau.data(), s.tau.data() + s.tau.size(), tau);
}

double load_factor(CoulombLoad law, double gravity) { return law == CoulombLoad::square ? gravity * gravity : std::abs(gravity); }

// Forward dynamics of the nominal model with the load-dependent friction moved to the torque side: the
// friction depends on (q, qd) only, so qdd = ABA(q, qd, tau - sum FCLj f_j(q) s_j(qd_j)).
class LoadFrictionDynamics final : public DirectForwardDynamics {
public:
    LoadFrictionDynamics(const LoadFrictionModel& model, std::unique_ptr<DirectForwardDynamics> nominal, Eigen::VectorXd levels)
        : model_(model), nominal_(std::move(nominal)), levels_(std::move(levels)), factors_(static_cast<std::size_t>(model.joint_count())),
          tau_(factors_.size()) {}
    bool accelerations(const double* q, const double* qd, const double* tau, double* qdd) override {
        model_.load_factors(q, factors_.data());
        std::copy(tau, tau + tau_.size(), tau_.begin());
        const auto& joints = model_.loaded_joints();
        for (std::size_t k = 0; k < joints.size(); ++k) {
            const auto j = static_cast<std::size_t>(joints[k]);
            tau_[j] -= levels_[static_cast<Eigen::Index>(k)] * factors_[j] * model_.sign(static_cast<int>(j), qd[j]);
        }
        return nominal_->accelerations(q, qd, tau_.data(), qdd);
    }

private:
    const LoadFrictionModel& model_;
    std::unique_ptr<DirectForwardDynamics> nominal_;
    Eigen::VectorXd levels_;  // FCLj in loaded_joints() order
    std::vector<double> factors_, tau_;
};

}  // namespace

const char* to_string(CoulombLoad law) {
    switch (law) {
        case CoulombLoad::abs: return "abs";
        case CoulombLoad::square: return "square";
        case CoulombLoad::none: break;
    }
    return "none";
}

LoadFrictionModel::LoadFrictionModel(std::unique_ptr<RobotModel> nominal, CoulombLoad law, const Eigen::VectorXd& reference,
                                     std::vector<CoulombSign> signs)
    : ModelExtension(std::move(nominal)), law_(law), signs_(std::move(signs)) {
    const int joints = this->nominal().joint_count();
    const int p = nominal_parameter_count();
    if (law_ == CoulombLoad::none) throw std::invalid_argument("load-dependent Coulomb friction: no law given (abs or square)");
    if (reference.size() != p) throw std::invalid_argument(fmt::format("load-dependent Coulomb friction: {} reference values for {} parameters", reference.size(), p));
    if (signs_.size() != static_cast<std::size_t>(joints)) {
        throw std::invalid_argument(fmt::format("load-dependent Coulomb friction: {} Coulomb sign functions for {} joints", signs_.size(), joints));
    }
    gravity_parameters_ = reference;
    const auto& names = this->nominal().parameter_names();
    for (int c = 0; c < p; ++c) {
        if (is_friction_or_offset(names[static_cast<std::size_t>(c)])) gravity_parameters_[c] = 0.0;
    }
    // A joint is loaded when its reference gravity torque is not identically 0: checked over poses spread
    // through every joint's turn (a fixed sequence, so that the parameter list never depends on chance).
    std::vector<double> peak(static_cast<std::size_t>(joints), 0.0), q(peak.size()), tau(peak.size());
    GravityScratch scratch;
    constexpr int kPoses = 24;
    for (int pose = 0; pose < kPoses; ++pose) {
        for (int j = 0; j < joints; ++j) q[static_cast<std::size_t>(j)] = std::fmod(0.7 + 2.39996322972865332 * (pose + 1) * (j + 1), 6.283185307179586) - 3.141592653589793;
        gravity_torques(this->nominal(), gravity_parameters_, q.data(), scratch, tau.data());
        for (int j = 0; j < joints; ++j) peak[static_cast<std::size_t>(j)] = std::max(peak[static_cast<std::size_t>(j)], std::abs(tau[static_cast<std::size_t>(j)]));
    }
    const double largest = *std::max_element(peak.begin(), peak.end());
    if (!(largest > 0.0) || !std::isfinite(largest)) {
        throw std::invalid_argument("load-dependent Coulomb friction: the reference parameters give no joint any gravity torque (a robot moving "
                                    "in a horizontal plane, or no inertial parameters: give them under parameters: or in the URDF)");
    }
    for (int j = 0; j < joints; ++j) {
        if (peak[static_cast<std::size_t>(j)] <= 1e-9 * largest) continue;
        loaded_.push_back(j);
        append_parameter(fmt::format("FCL{}", j + 1));
    }
}

void LoadFrictionModel::load_factors(const double* q, double* factors) const {
    // One scratch per thread: the pipeline evaluates regressors on several threads at once.
    thread_local GravityScratch scratch;
    gravity_torques(nominal(), gravity_parameters_, q, scratch, factors);
    for (int j = 0; j < joint_count(); ++j) factors[j] = load_factor(law_, factors[j]);
}

void LoadFrictionModel::write_load_columns(const double* q, const double* qd, Eigen::Ref<Eigen::MatrixXd> D) const {
    const int p = nominal_parameter_count();
    D.rightCols(D.cols() - p).setZero();
    thread_local std::vector<double> factors;
    factors.resize(static_cast<std::size_t>(joint_count()));
    load_factors(q, factors.data());
    for (std::size_t k = 0; k < loaded_.size(); ++k) {
        const int j = loaded_[k];
        D(j, p + static_cast<int>(k)) = factors[static_cast<std::size_t>(j)] * sign(j, qd[j]);
    }
}

void LoadFrictionModel::regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const {
    nominal().regressor(q, qd, qdd, D.leftCols(nominal_parameter_count()));
    write_load_columns(q, qd, D);
}

void LoadFrictionModel::coulomb_columns(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const {
    nominal().coulomb_columns(q, qd, qdd, D.leftCols(nominal_parameter_count()));
    write_load_columns(q, qd, D);
}

bool LoadFrictionModel::inverse_dynamics(const double* q, const double* qd, const double* qdd, const Eigen::VectorXd& X, double* tau) const {
    const int p = nominal_parameter_count();
    if (!nominal().inverse_dynamics(q, qd, qdd, X.head(p), tau)) return false;
    thread_local std::vector<double> factors;
    factors.resize(static_cast<std::size_t>(joint_count()));
    load_factors(q, factors.data());
    for (std::size_t k = 0; k < loaded_.size(); ++k) {
        const int j = loaded_[k];
        tau[j] += X[p + static_cast<Eigen::Index>(k)] * factors[static_cast<std::size_t>(j)] * sign(j, qd[j]);
    }
    return true;
}

std::unique_ptr<DirectForwardDynamics> LoadFrictionModel::articulated_body(const Eigen::VectorXd& X) const {
    const int p = nominal_parameter_count();
    std::unique_ptr<DirectForwardDynamics> inner = nominal().articulated_body(X.head(p));
    if (!inner) return nullptr;
    return std::make_unique<LoadFrictionDynamics>(*this, std::move(inner), X.tail(X.size() - p));
}

}  // namespace jacobid::robot
