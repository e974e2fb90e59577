// SPDX-License-Identifier: MIT
#include "identify/friction/coulomb_smoothing.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "identify/friction/shape_selection.hpp"
#include "jacobid/robot/coulomb_sign.hpp"

namespace jacobid::identify {
namespace {

// Column s_a(qd_j) per candidate a (Coulomb friction acts on its own joint only).
class SmoothedSigns final : public CandidateColumns {
public:
    explicit SmoothedSigns(const std::vector<double>& candidates) : candidates_(candidates) {}
    void values(int joint, const double* qd, const double*, double* out) const override {
        for (std::size_t c = 0; c < candidates_.size(); ++c) out[c] = robot::CoulombSign{robot::CoulombModel::SmoothAtan, candidates_[c]}(qd[joint]);
    }

private:
    std::vector<double> candidates_;
};

}  // namespace

std::vector<double> default_coulomb_candidates() {
    std::vector<double> a;
    for (int k = 0; k <= 14; ++k) a.push_back(10.0 * std::pow(2.0, 0.5 * k));
    return a;
}

std::vector<double> CoulombSmoothingChoice::alphas() const {
    std::vector<double> a;
    for (const auto& j : joints) a.push_back(j.alpha);
    return a;
}

CoulombSmoothingChoice choose_coulomb_smoothing(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& settings,
                                                double fallback_alpha, const CoulombSmoothingSettings& smoothing) {
    CoulombSmoothingChoice out;
    out.candidates = smoothing.candidates.empty() ? default_coulomb_candidates() : smoothing.candidates;
    const int joints = model.joint_count();
    ShapeSelectionSettings selection;
    selection.candidates = out.candidates;
    selection.folds = smoothing.folds;
    selection.weighted = smoothing.weighted;
    for (int j = 0; j < joints; ++j) {
        selection.target.push_back(model.parameter_index(fmt::format("FC{}", j + 1)));
        // Start from the candidate nearest to the description's alpha (on a log scale).
        int nearest = 0;
        for (std::size_t c = 1; c < out.candidates.size(); ++c) {
            if (std::abs(std::log(out.candidates[c] / fallback_alpha)) < std::abs(std::log(out.candidates[static_cast<std::size_t>(nearest)] / fallback_alpha))) {
                nearest = static_cast<int>(c);
            }
        }
        selection.start.push_back(nearest);
    }
    const ShapeChoice shape = choose_shape(model, SmoothedSigns(out.candidates), log, settings, selection);
    out.folds = shape.folds;
    out.passes = shape.passes;
    out.common_alpha = shape.common >= 0 ? out.candidates[static_cast<std::size_t>(shape.common)] : 0.0;
    out.common_score = shape.common_score;
    for (int j = 0; j < joints; ++j) {
        const JointShape& s = shape.joints[static_cast<std::size_t>(j)];
        JointSmoothing js;
        js.chosen = s.chosen;
        js.alpha = s.chosen ? out.candidates[static_cast<std::size_t>(s.index)] : fallback_alpha;
        js.reason = selection.target[static_cast<std::size_t>(j)] < 0 ? fmt::format("the model has no FC{}", j + 1) : s.reason;
        js.heldout_rms = s.heldout_rms;
        out.joints.push_back(js);
    }
    return out;
}

std::string describe(const CoulombSmoothingChoice& choice, const std::vector<std::string>& joint_names) {
    std::string chosen, kept;
    for (std::size_t j = 0; j < choice.joints.size(); ++j) {
        const JointSmoothing& js = choice.joints[j];
        const std::string name = j < joint_names.size() ? joint_names[j] : fmt::format("j{}", j + 1);
        if (js.chosen) chosen += fmt::format("{}{} {:.4g}", chosen.empty() ? "" : ", ", name, js.alpha);
        else kept += fmt::format("; {} kept {:.4g} ({})", name, js.alpha, js.reason);
    }
    const std::string common = choice.common_alpha > 0.0 ? fmt::format("common {:.4g}, then ", choice.common_alpha) : "";
    return fmt::format("Coulomb smoothing alpha: auto, by {}-block held-out error over {} candidates {:.3g}..{:.4g}: {}{}{}{}", choice.folds,
                       choice.candidates.size(), choice.candidates.front(), choice.candidates.back(), common,
                       chosen.empty() ? "no joint chosen" : chosen, chosen.empty() ? "" : " s/rad", kept);
}

SmoothedModel resolve_coulomb_smoothing(const robot::RobotDescription& description, const robot::RobotModel& nominal, const LogColumns& log,
                                        const PipelineSettings& settings, bool weighted) {
    SmoothedModel m;
    const auto* presliding = dynamic_cast<const robot::PreslidingModel*>(&nominal);
    if (presliding && description.presliding_displacement_auto && description.presliding_displacements.empty()) {
        m.presliding = choose_presliding_displacement(*presliding, log, settings, description.presliding_displacement, weighted);
        make_chosen_model(description, m);
    }
    if (!description.coulomb_alpha_auto || description.coulomb.model != robot::CoulombModel::SmoothAtan) return m;
    CoulombSmoothingSettings smoothing;
    smoothing.weighted = weighted;
    m.choice = choose_coulomb_smoothing(m.get(nominal), log, settings, description.coulomb.alpha, smoothing);
    make_chosen_model(description, m);
    return m;
}

void make_chosen_model(const robot::RobotDescription& description, SmoothedModel& m) {
    m.chosen.reset();
    if (!m.presliding && !m.choice) return;
    robot::RobotDescription chosen = description;
    if (m.presliding) chosen.presliding_displacements = m.presliding->displacement;
    if (m.choice) chosen.coulomb_alpha = m.choice->alphas();
    m.chosen = robot::make_robot_model(chosen);
}

}  // namespace jacobid::identify
