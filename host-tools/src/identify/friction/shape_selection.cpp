// SPDX-License-Identifier: MIT
#include "identify/friction/shape_selection.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "identify/solve/normal_equations.hpp"

namespace jacobid::identify {
namespace {

// The nominal regressor followed by, for every joint with a target column, one column per candidate on
// that joint's row (friction acts on its own joint only). Its history is the nominal model's followed by the
// candidates'.
class CandidateModel final : public robot::RobotModel {
public:
    CandidateModel(const robot::RobotModel& nominal, const CandidateColumns& columns, const std::vector<int>& target,
                   const std::vector<double>& candidates)
        : nominal_(nominal), columns_(columns), target_(target), candidates_(candidates), names_(nominal.parameter_names()) {
        for (std::size_t j = 0; j < target_.size(); ++j) {
            first_.push_back(target_[j] < 0 ? -1 : static_cast<int>(names_.size()));
            if (target_[j] < 0) continue;
            for (const double a : candidates_) names_.push_back(fmt::format("{}@{:g}", nominal.parameter_names()[static_cast<std::size_t>(target_[j])], a));
        }
        values_.resize(candidates_.size());
    }
    std::string model_name() const override { return nominal_.model_name(); }
    int joint_count() const override { return nominal_.joint_count(); }
    int parameter_count() const override { return static_cast<int>(names_.size()); }
    const std::vector<std::string>& parameter_names() const override { return names_; }
    // regressor() keeps the velocities for history_columns() of the same sample (qd_ below): one thread only.
    bool concurrent_regressor() const override { return false; }
    void regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const override {
        const int p = nominal_.parameter_count();
        nominal_.regressor(q, qd, qdd, D.leftCols(p));
        D.rightCols(D.cols() - p).setZero();
        qd_.assign(qd, qd + joint_count());
        if (columns_.history_size() == 0) write_candidates(nullptr, D);
    }
    int history_size() const override { return nominal_.history_size() + columns_.history_size(); }
    void integrate_history(const std::vector<const std::vector<double>*>& q, std::vector<double>& state) const override {
        std::vector<double> nominal, candidates;
        nominal_.integrate_history(q, nominal);
        columns_.integrate_history(q, candidates);
        const auto a = static_cast<std::size_t>(nominal_.history_size()), b = static_cast<std::size_t>(columns_.history_size());
        const std::size_t n = q.empty() ? 0 : q.front()->size();
        state.assign(n * (a + b), 0.0);
        for (std::size_t k = 0; k < n; ++k) {
            std::copy_n(nominal.data() + k * a, a, state.data() + k * (a + b));
            std::copy_n(candidates.data() + k * b, b, state.data() + k * (a + b) + a);
        }
    }
    void history_columns(const double* state, Eigen::Ref<Eigen::MatrixXd> D) const override {
        nominal_.history_columns(state, D.leftCols(nominal_.parameter_count()));
        write_candidates(state + nominal_.history_size(), D);
    }
    // First candidate column of joint j (-1: the joint has no Coulomb column).
    int first_candidate(std::size_t joint) const { return first_[joint]; }

private:
    // The candidate columns from the velocities of the last regressor call (the pipeline calls
    // history_columns right after regressor for the same sample) or from the candidates' history.
    void write_candidates(const double* history, Eigen::Ref<Eigen::MatrixXd> D) const {
        for (std::size_t j = 0; j < first_.size(); ++j) {
            if (first_[j] < 0) continue;
            columns_.values(static_cast<int>(j), qd_.data(), history, values_.data());
            for (std::size_t c = 0; c < candidates_.size(); ++c) D(static_cast<Eigen::Index>(j), first_[j] + static_cast<Eigen::Index>(c)) = values_[c];
        }
    }

    const robot::RobotModel& nominal_;
    const CandidateColumns& columns_;
    std::vector<int> target_;
    std::vector<double> candidates_;
    std::vector<int> first_;
    std::vector<std::string> names_;
    mutable std::vector<double> qd_, values_;  // per-call scratch (the pipeline calls from one thread)
};

// Per joint and per contiguous block of the log, the Gram matrix of the joint's own row over
// [nominal columns, the joint's candidate columns, Y] ("local" columns).
class BlockGramSink final : public RowSink {
public:
    BlockGramSink(const CandidateModel& model, int nominal, int candidates, int blocks, std::size_t samples)
        : model_(model), nominal_(nominal), candidates_(candidates), blocks_(blocks), samples_(std::max<std::size_t>(samples, 1)) {
        const int joints = model.joint_count();
        gram_.resize(static_cast<std::size_t>(joints));
        rows_.assign(static_cast<std::size_t>(joints), std::vector<double>(static_cast<std::size_t>(blocks), 0.0));
        for (int j = 0; j < joints; ++j) {
            const Eigen::Index n = local_columns(j) + 1;
            gram_[static_cast<std::size_t>(j)].assign(static_cast<std::size_t>(blocks), Eigen::MatrixXd::Zero(n, n));
        }
    }
    void row(const DecimatedRow& r) override {
        const int block = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(blocks_) - 1, r.sample * static_cast<std::size_t>(blocks_) / samples_));
        for (int j = 0; j < model_.joint_count(); ++j) {
            const Eigen::Index own = local_columns(j);
            z_.resize(own + 1);
            z_.head(nominal_) = r.w.row(j).head(nominal_).transpose();
            const int first = model_.first_candidate(static_cast<std::size_t>(j));
            if (first >= 0) z_.segment(nominal_, candidates_) = r.w.row(j).segment(first, candidates_).transpose();
            z_[own] = r.y[j];
            gram_[static_cast<std::size_t>(j)][static_cast<std::size_t>(block)].selfadjointView<Eigen::Lower>().rankUpdate(z_);
            rows_[static_cast<std::size_t>(j)][static_cast<std::size_t>(block)] += 1.0;
        }
    }
    // The accumulated lower triangles made symmetric.
    void finish() {
        for (auto& joint : gram_) {
            for (auto& g : joint) g = g.selfadjointView<Eigen::Lower>();
        }
    }
    Eigen::Index local_columns(int joint) const { return nominal_ + (model_.first_candidate(static_cast<std::size_t>(joint)) >= 0 ? candidates_ : 0); }
    const Eigen::MatrixXd& gram(int joint, int block) const { return gram_[static_cast<std::size_t>(joint)][static_cast<std::size_t>(block)]; }
    double rows(int joint, int block) const { return rows_[static_cast<std::size_t>(joint)][static_cast<std::size_t>(block)]; }

private:
    const CandidateModel& model_;
    int nominal_, candidates_, blocks_;
    std::size_t samples_;
    std::vector<std::vector<Eigen::MatrixXd>> gram_;  // [joint][block]
    std::vector<std::vector<double>> rows_;
    Eigen::VectorXd z_;
};

class HeldOutSelection {
public:
    HeldOutSelection(const BlockGramSink& grams, int nominal, int joints, int blocks, const std::vector<int>& target)
        : grams_(grams), nominal_(nominal), joints_(joints), blocks_(blocks), target_(target), weight2_(static_cast<std::size_t>(joints), 1.0) {}

    void set_weights(std::vector<double> weight2) { weight2_ = std::move(weight2); }

    // Normal equations in nominal column order, joint j's FC column taken from candidate choice[j] (-1:
    // the nominal column), summed over the joints (weighted) and over the blocks (all but `block` when
    // exclude, only `block` otherwise; every block when block < 0), or one joint's unweighted rows.
    GramSums sum(const std::vector<int>& choice, int block, bool exclude, int only_joint = -1) const {
        GramSums s;
        s.G = Eigen::MatrixXd::Zero(nominal_, nominal_);
        s.b = Eigen::VectorXd::Zero(nominal_);
        std::vector<Eigen::Index> index(static_cast<std::size_t>(nominal_));
        for (int j = 0; j < joints_; ++j) {
            if (only_joint >= 0 && j != only_joint) continue;
            const double w = only_joint >= 0 ? 1.0 : weight2_[static_cast<std::size_t>(j)];
            for (int c = 0; c < nominal_; ++c) index[static_cast<std::size_t>(c)] = c;
            const int own = choice[static_cast<std::size_t>(j)];
            if (own >= 0) index[static_cast<std::size_t>(target_[static_cast<std::size_t>(j)])] = nominal_ + own;
            const Eigen::Index y = grams_.local_columns(j);
            for (int b = 0; b < blocks_; ++b) {
                if (block >= 0 && (exclude ? b == block : b != block)) continue;
                const Eigen::MatrixXd& g = grams_.gram(j, b);
                s.G += w * g(index, index);
                s.b += w * g(index, y);
                s.yy += w * g(y, y);
                s.rows += grams_.rows(j, b);
            }
        }
        return s;
    }

    // Blocked cross-validation: joint j's torque on every block predicted by the fit on the other blocks;
    // per block, the mean squared error (N.m^2).
    std::vector<double> heldout_mse(const std::vector<int>& choice, int joint) const {
        std::vector<double> mse;
        for (int b = 0; b < blocks_; ++b) {
            const Eigen::VectorXd x = solve_minimum_norm(sum(choice, b, true));
            const GramSums held = sum(choice, b, false, joint);
            mse.push_back(held.rows > 0.0 ? prediction_sse(held, x) / held.rows : std::numeric_limits<double>::quiet_NaN());
        }
        return mse;
    }

private:
    const BlockGramSink& grams_;
    int nominal_, joints_, blocks_;
    std::vector<int> target_;
    std::vector<double> weight2_;
};

double mean(const std::vector<double>& v) {
    double s = 0.0;
    for (const double x : v) s += x;
    return v.empty() ? std::numeric_limits<double>::quiet_NaN() : s / static_cast<double>(v.size());
}

// Standard error of the mean of the block-by-block difference a - b.
double paired_standard_error(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> d;
    for (std::size_t k = 0; k < a.size() && k < b.size(); ++k) d.push_back(a[k] - b[k]);
    if (d.size() < 2) return 0.0;
    const double m = mean(d);
    double var = 0.0;
    for (const double x : d) var += (x - m) * (x - m);
    return std::sqrt(var / static_cast<double>(d.size() - 1) / static_cast<double>(d.size()));
}

// A joint leaves the common choice only on evidence: for the candidate with the smallest mean held-out
// error, when it beats the current one by more than `k_se` standard errors of their block-by-block
// difference. On real drives the held-out error is flat over a decade of alpha (a few per mille between 300
// and 1280 s/rad on the UR10e's wrists), so its minimum alone is noise (docs/method.md, "Coulomb smoothing
// from data").
int significant_choice(const std::vector<std::vector<double>>& mse, int current, double k_se) {
    int best = current;
    for (int c = 0; c < static_cast<int>(mse.size()); ++c) {
        if (mean(mse[static_cast<std::size_t>(c)]) < mean(mse[static_cast<std::size_t>(best)])) best = c;
    }
    if (best == current) return current;
    const std::vector<double>& now = mse[static_cast<std::size_t>(current)];
    const std::vector<double>& better = mse[static_cast<std::size_t>(best)];
    return mean(now) - mean(better) > k_se * paired_standard_error(now, better) ? best : current;
}

}  // namespace

ShapeChoice choose_shape(const robot::RobotModel& model, const CandidateColumns& columns, const LogColumns& log, const PipelineSettings& settings,
                         const ShapeSelectionSettings& selection_settings) {
    ShapeChoice out;
    out.folds = std::max(2, selection_settings.folds);
    const int joints = model.joint_count();
    const int nominal = model.parameter_count();
    const std::vector<double>& values = selection_settings.candidates;
    const int candidates = static_cast<int>(values.size());
    const std::vector<int>& target = selection_settings.target;
    out.joints.resize(static_cast<std::size_t>(joints));

    const CandidateModel candidate_model(model, columns, target, values);
    BlockGramSink grams(candidate_model, nominal, candidates, out.folds, log.samples());
    PipelineSettings candidate_settings = settings;
    candidate_settings.residual_lags = 0;  // the choice needs the block Grams only, not the final fit's lagged products
    candidate_settings.plot_rows = 0;
    const PipelineOutput run = run_pipeline(candidate_model, log, candidate_settings, &grams);
    grams.finish();

    // The joints whose shape is chosen; the others keep the nominal column.
    std::vector<int> choice(static_cast<std::size_t>(joints), -1);
    std::vector<int> free_joints;
    for (int j = 0; j < joints; ++j) {
        const auto js = static_cast<std::size_t>(j);
        if (target[js] < 0) continue;
        if (js < run.info.joint_moves.size() && !run.info.joint_moves[js]) {
            out.joints[js].reason = "the joint does not move";
            continue;
        }
        free_joints.push_back(j);
        choice[js] = selection_settings.start[js];
    }
    HeldOutSelection selection(grams, nominal, joints, out.folds, target);
    if (selection_settings.weighted) {
        // Gautier's weights from an OLS fit on all rows at the starting choice, as identify --weighted.
        const Eigen::VectorXd x = solve_minimum_norm(selection.sum(choice, -1, false));
        std::vector<double> weight2;
        for (int j = 0; j < joints; ++j) {
            const GramSums own = selection.sum(choice, -1, false, j);
            const double sigma2 = own.rows > 0.0 ? prediction_sse(own, x) / own.rows : 0.0;
            weight2.push_back(sigma2 > 0.0 ? 1.0 / sigma2 : 1.0);
        }
        selection.set_weights(std::move(weight2));
    }

    // 1. One value for every joint: the candidate with the smallest sum over the joints of the held-out
    //    mean squared error relative to the joint's mean square torque (joints of different torque scales count alike).
    if (!free_joints.empty()) {
        std::vector<double> mean_square(static_cast<std::size_t>(joints), 1.0);
        for (const int j : free_joints) {
            const GramSums own = selection.sum(choice, -1, false, j);
            mean_square[static_cast<std::size_t>(j)] = own.rows > 0.0 && own.yy > 0.0 ? own.yy / own.rows : 1.0;
        }
        double best_score = std::numeric_limits<double>::infinity();
        int common = choice[static_cast<std::size_t>(free_joints.front())];
        std::vector<int> trial = choice;
        for (int c = 0; c < candidates; ++c) {
            for (const int j : free_joints) trial[static_cast<std::size_t>(j)] = c;
            double score = 0.0;
            for (const int j : free_joints) score += mean(selection.heldout_mse(trial, j)) / mean_square[static_cast<std::size_t>(j)];
            out.common_score.push_back(score);
            if (score < best_score) best_score = score, common = c;
        }
        out.common = common;
        for (const int j : free_joints) choice[static_cast<std::size_t>(j)] = common;
    }
    // 2. Per joint, by coordinate descent: a joint moves away from the common value only on evidence.
    std::vector<std::vector<double>> rms(static_cast<std::size_t>(joints));
    for (out.passes = 1; out.passes <= 4 && !free_joints.empty(); ++out.passes) {
        bool changed = false;
        for (const int j : free_joints) {
            std::vector<int> trial = choice;
            std::vector<std::vector<double>> mse;  // [candidate][block]
            for (int c = 0; c < candidates; ++c) {
                trial[static_cast<std::size_t>(j)] = c;
                mse.push_back(selection.heldout_mse(trial, j));
            }
            const int pick = significant_choice(mse, choice[static_cast<std::size_t>(j)], 1.0);
            std::vector<double>& errors = rms[static_cast<std::size_t>(j)];
            errors.clear();
            for (const auto& m : mse) errors.push_back(std::sqrt(mean(m)));
            if (pick != choice[static_cast<std::size_t>(j)]) changed = true;
            choice[static_cast<std::size_t>(j)] = pick;
        }
        if (!changed) break;
    }
    out.passes = free_joints.empty() ? 0 : std::min(out.passes, 4);
    for (const int j : free_joints) {
        auto& js = out.joints[static_cast<std::size_t>(j)];
        js.chosen = true;
        js.index = choice[static_cast<std::size_t>(j)];
        js.heldout_rms = rms[static_cast<std::size_t>(j)];
    }
    return out;
}

}  // namespace jacobid::identify
