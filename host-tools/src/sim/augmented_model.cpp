// SPDX-License-Identifier: MIT
#include "sim/augmented_model.hpp"

#include "robot/presliding_model.hpp"

#include <algorithm>
#include <memory>
#include <utility>

namespace jacobid::sim {
namespace {
// Columns of the form f(q) s(qd_j), which the identification evaluates on the Coulomb velocity
// (RobotModel::coulomb_column_indices).
bool is_sign_column(EffectKind kind) { return kind == EffectKind::CoulombSmoothing || kind == EffectKind::CoulombLoad; }

// Forward dynamics of the nominal model with the terms' torques moved to the torque side: none of them
// depends on qdd (AugmentedModel::articulated_body checks), so qdd = ABA(q, qd, tau - sum_t C_t(q, qd) x_t).
class AugmentedDynamics final : public robot::DirectForwardDynamics {
public:
    AugmentedDynamics(const AugmentedModel& model, std::unique_ptr<robot::DirectForwardDynamics> nominal, Eigen::VectorXd X)
        : model_(model), nominal_(std::move(nominal)), X_(std::move(X)), zero_(static_cast<std::size_t>(model.joint_count()), 0.0),
          tau_(zero_.size()) {
        int widest = 0;
        for (const auto& t : model.terms()) widest = std::max(widest, t.column_count());
        columns_.resize(model.joint_count(), widest);
    }
    bool accelerations(const double* q, const double* qd, const double* tau, double* qdd) override {
        std::fill(tau_.begin(), tau_.end(), 0.0);
        model_.add_term_torques(q, qd, zero_.data(), X_, columns_, tau_.data());
        for (std::size_t j = 0; j < tau_.size(); ++j) tau_[j] = tau[j] - tau_[j];
        return nominal_->accelerations(q, qd, tau_.data(), qdd);
    }

private:
    const AugmentedModel& model_;
    std::unique_ptr<robot::DirectForwardDynamics> nominal_;
    Eigen::VectorXd X_;
    std::vector<double> zero_, tau_;
    Eigen::MatrixXd columns_;
};
}  // namespace

AugmentedModel::AugmentedModel(const robot::RobotModel& nominal, EffectContext context, std::vector<EffectTerm> terms)
    : ModelExtension(nominal), context_(std::move(context)) {
    for (const auto& t : terms) {
        if (t.column_count() == 0) continue;
        terms_.push_back(t);
        first_column_.push_back(parameter_count());
        for (auto& name : t.column_names()) append_parameter(std::move(name));
        if (effect_has_history(t.kind)) history_terms_.push_back(terms_.size() - 1);
        load_terms_ = load_terms_ || t.kind == EffectKind::CoulombLoad;
    }
}

const double* AugmentedModel::load_factors(const double* q) const {
    if (!load_terms_) return nullptr;
    thread_local std::vector<double> factors;  // regressors run on several threads at once
    factors.resize(static_cast<std::size_t>(context_.joints));
    context_.load->load_factors(q, factors.data());
    return factors.data();
}

void AugmentedModel::coulomb_columns(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const {
    nominal().coulomb_columns(q, qd, qdd, D.leftCols(nominal_parameter_count()));
    const double* factors = load_factors(q);
    for (std::size_t t = 0; t < terms_.size(); ++t) {
        if (!is_sign_column(terms_[t].kind)) continue;
        term_columns(terms_[t], context_, q, qd, qdd, D.middleCols(first_column_[t], terms_[t].column_count()), factors);
    }
}

std::vector<int> AugmentedModel::coulomb_column_indices() const {
    std::vector<int> columns = nominal().coulomb_column_indices();
    for (std::size_t t = 0; t < terms_.size(); ++t) {
        if (is_sign_column(terms_[t].kind)) columns.push_back(first_column_[t]);
    }
    return columns;
}

void AugmentedModel::integrate_history(const std::vector<const std::vector<double>*>& q, std::vector<double>& state) const {
    const auto nominal_width = static_cast<std::size_t>(nominal().history_size());
    if (history_terms_.empty()) {
        nominal().integrate_history(q, state);
        return;
    }
    const std::size_t n = q.empty() ? 0 : q.front()->size(), width = static_cast<std::size_t>(history_size());
    std::vector<double> nominal_state;
    if (nominal_width > 0) nominal().integrate_history(q, nominal_state);
    state.assign(n * width, 0.0);
    for (std::size_t k = 0; k < n && nominal_width > 0; ++k) {
        std::copy(nominal_state.begin() + static_cast<std::ptrdiff_t>(k * nominal_width),
                  nominal_state.begin() + static_cast<std::ptrdiff_t>((k + 1) * nominal_width), state.begin() + static_cast<std::ptrdiff_t>(k * width));
    }
    for (std::size_t h = 0; h < history_terms_.size(); ++h) {
        const EffectTerm& t = terms_[history_terms_[h]];
        const std::vector<double> s = robot::presliding_states(*q[static_cast<std::size_t>(t.joint)], t.displacement, context_.presliding_play);
        for (std::size_t k = 0; k < n; ++k) state[k * width + nominal_width + h] = s[k];
    }
}

void AugmentedModel::history_columns(const double* state, Eigen::Ref<Eigen::MatrixXd> D) const {
    const int nominal_width = nominal().history_size();
    if (nominal_width > 0) nominal().history_columns(state, D.leftCols(nominal_parameter_count()));
    for (std::size_t h = 0; h < history_terms_.size(); ++h) {
        const std::size_t t = history_terms_[h];
        D(terms_[t].joint, first_column_[t]) = state[static_cast<std::size_t>(nominal_width) + h];
    }
}

void AugmentedModel::add_term_torques(const double* q, const double* qd, const double* qdd, const Eigen::VectorXd& X,
                                      Eigen::MatrixXd& columns, double* tau) const {
    const double* factors = load_factors(q);
    for (std::size_t t = 0; t < terms_.size(); ++t) {
        const int count = terms_[t].column_count();
        if (columns.rows() != joint_count() || columns.cols() < count) columns.resize(joint_count(), count);
        auto block = columns.leftCols(count);
        term_columns(terms_[t], context_, q, qd, qdd, block, factors);
        const auto values = X.segment(first_column_[t], count);
        for (int j = 0; j < joint_count(); ++j) tau[j] += block.row(j).dot(values);
    }
}

bool AugmentedModel::inverse_dynamics(const double* q, const double* qd, const double* qdd, const Eigen::VectorXd& X, double* tau) const {
    if (!nominal().inverse_dynamics(q, qd, qdd, X.head(nominal_parameter_count()), tau)) return false;
    thread_local Eigen::MatrixXd columns;  // inverse dynamics runs on several threads at once
    add_term_torques(q, qd, qdd, X, columns, tau);
    return true;
}

std::unique_ptr<robot::DirectForwardDynamics> AugmentedModel::articulated_body(const Eigen::VectorXd& X) const {
    for (const auto& t : terms_) {
        if (t.kind == EffectKind::RotorInertia) return nullptr;
    }
    std::unique_ptr<robot::DirectForwardDynamics> inner = nominal().articulated_body(X.head(nominal_parameter_count()));
    if (!inner) return nullptr;
    return std::make_unique<AugmentedDynamics>(*this, std::move(inner), X);
}

void AugmentedModel::regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const {
    const int c0 = nominal_parameter_count();
    nominal().regressor(q, qd, qdd, D.leftCols(c0));
    const double* factors = load_factors(q);
    for (std::size_t t = 0; t < terms_.size(); ++t) {
        term_columns(terms_[t], context_, q, qd, qdd, D.middleCols(first_column_[t], terms_[t].column_count()), factors);
    }
}

}  // namespace jacobid::sim
