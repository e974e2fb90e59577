// SPDX-License-Identifier: MIT
#include "identify/friction/presliding_displacement.hpp"

#include <fmt/core.h>

#include <cmath>

namespace jacobid::identify {
namespace {

// Joint j's Dahl state at every candidate x_p, along the same play-filtered positions as the final model.
class DahlCandidates final : public CandidateColumns {
public:
    DahlCandidates(const std::vector<double>& candidates, double play_width, int joints)
        : candidates_(candidates), play_width_(play_width), joints_(joints) {}
    int history_size() const override { return joints_ * static_cast<int>(candidates_.size()); }
    void integrate_history(const std::vector<const std::vector<double>*>& q, std::vector<double>& state) const override {
        const std::size_t n = q.empty() ? 0 : q.front()->size(), width = static_cast<std::size_t>(history_size());
        state.assign(n * width, 0.0);
        for (std::size_t j = 0; j < q.size(); ++j) {
            for (std::size_t c = 0; c < candidates_.size(); ++c) {
                const std::vector<double> s = robot::presliding_states(*q[j], candidates_[c], play_width_);
                for (std::size_t k = 0; k < n; ++k) state[k * width + j * candidates_.size() + c] = s[k];
            }
        }
    }
    void values(int joint, const double*, const double* history, double* out) const override {
        const std::size_t c0 = static_cast<std::size_t>(joint) * candidates_.size();
        for (std::size_t c = 0; c < candidates_.size(); ++c) out[c] = history[c0 + c];
    }

private:
    std::vector<double> candidates_;
    double play_width_;
    int joints_;
};

}  // namespace

std::vector<double> default_presliding_candidates() {
    std::vector<double> x;
    for (int k = 0; k <= 12; ++k) x.push_back(5e-5 * std::pow(2.0, 0.5 * k));
    return x;
}

PreslidingDisplacementChoice choose_presliding_displacement(const robot::PreslidingModel& model, const LogColumns& log,
                                                            const PipelineSettings& settings, double fallback, bool weighted,
                                                            std::vector<double> candidates) {
    PreslidingDisplacementChoice out;
    out.candidates = candidates.empty() ? default_presliding_candidates() : std::move(candidates);
    const int joints = model.joint_count();
    ShapeSelectionSettings selection;
    selection.candidates = out.candidates;
    selection.weighted = weighted;
    int nearest = 0;  // the candidate nearest to the fallback (log scale), where the search starts
    for (std::size_t c = 1; c < out.candidates.size(); ++c) {
        if (std::abs(std::log(out.candidates[c] / fallback)) < std::abs(std::log(out.candidates[static_cast<std::size_t>(nearest)] / fallback))) {
            nearest = static_cast<int>(c);
        }
    }
    for (int j = 0; j < joints; ++j) {
        selection.target.push_back(model.first_presliding_column() + j);
        selection.start.push_back(nearest);
    }
    const DahlCandidates columns(out.candidates, model.settings().play_width, joints);
    out.shape = choose_shape(model, columns, log, settings, selection);
    for (const JointShape& s : out.shape.joints) out.displacement.push_back(s.chosen ? out.candidates[static_cast<std::size_t>(s.index)] : fallback);
    return out;
}

std::string describe(const PreslidingDisplacementChoice& choice, const std::vector<std::string>& joint_names) {
    std::string chosen, kept;
    for (std::size_t j = 0; j < choice.shape.joints.size(); ++j) {
        const JointShape& js = choice.shape.joints[j];
        const std::string name = j < joint_names.size() ? joint_names[j] : fmt::format("j{}", j + 1);
        if (js.chosen) chosen += fmt::format("{}{} {:.3g}", chosen.empty() ? "" : ", ", name, choice.displacement[j]);
        else kept += fmt::format("; {} kept {:.3g} ({})", name, choice.displacement[j], js.reason);
    }
    const std::string common = choice.shape.common >= 0 ? fmt::format("common {:.3g}, then ", choice.candidates[static_cast<std::size_t>(choice.shape.common)]) : "";
    return fmt::format("presliding displacement x_p: auto, by {}-block held-out error over {} candidates {:.3g}..{:.3g} rad: {}{}{}{}",
                       choice.shape.folds, choice.candidates.size(), choice.candidates.front(), choice.candidates.back(), common,
                       chosen.empty() ? "no joint chosen" : chosen, chosen.empty() ? "" : " rad", kept);
}

}  // namespace jacobid::identify
