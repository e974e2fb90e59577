// SPDX-License-Identifier: MIT
#pragma once
// Forward stepwise selection of the missing effects. Each step fits the current model (nominal columns +
// effects accepted so far, torque channel shifted by the accepted delay) and tries every remaining
// candidate: its columns added (a torque_delay candidate: the delay searched on a grid of one sample and
// refined by a parabola through the best three). A candidate is accepted only if
//   1. it is significant with an honest sample size: the filtered, decimated residuals are correlated, so
//      the chi-square statistic dRSS / sigma^2 is divided by n / n_eff (n_eff from the residual
//      autocorrelation, Bartlett), and its p-value, Bonferroni-corrected over every candidate and grid
//      point tried in the step, must be below alpha; and
//   2. it reduces the held-out error (validation log or blocked cross-validation) by at least min_gain.
// Of the candidates that pass, the one with the largest penalized improvement chi2 - dof ln(n_eff) is
// accepted; the loop ends when none passes.
#include <functional>
#include <string>
#include <vector>

#include "diagnose/decimated_rows.hpp"
#include "sim/augmented_model.hpp"

namespace jacobid::diagnose {

struct SelectionSettings {
    double alpha = 1e-3;
    double min_gain = 0.05;
    int max_effects = 4;
    int folds = 5;
    double max_delay = 0.02;  // s, delays searched in [-max_delay, max_delay]
    bool search_delay = true;
};

struct CandidateTest {
    sim::EffectTerm term;       // kind TorqueDelay for the delay candidate
    double delay = 0.0;         // s, the delay candidate's estimate
    int dof = 0;
    double chi2 = 0.0;          // after the n / n_eff correction
    double p_value = 1.0;
    double adjusted_p = 1.0;    // Bonferroni
    double heldout_before = 0.0, heldout_after = 0.0;  // weighted RMS (units of each joint's nominal sigma)
    double gain = 0.0;          // 1 - after / before
    double value = 0.0, std = 0.0;
    double score = 0.0;
    bool significant = false, generalizes = false;
    bool accepted() const { return significant && generalizes; }
    std::string label() const;
};

struct SelectionStep {
    double rows = 0.0, n_eff = 0.0;
    double heldout = 0.0;
    std::size_t tested = 0;
    std::vector<CandidateTest> top;  // best candidates by score, at most 5
    bool accepted = false;           // top.front() was accepted
};

struct SelectionResult {
    std::vector<CandidateTest> accepted;  // in order of acceptance
    std::vector<sim::EffectTerm> terms;   // accepted column terms
    double delay = 0.0;
    std::vector<SelectionStep> steps;
    std::vector<double> joint_sigma;      // nominal residual RMS per joint (the row weights are 1 / sigma)
    std::vector<std::string> skipped;     // candidates collinear with the model (e.g. rotor inertia of joint 1 in ZZ1R)
    std::vector<std::string> unexcited;   // nominal parameters the log does not excite (zero or collinear columns), left out
    std::string heldout_kind;
};

// `catalogue` is the nominal model augmented with every candidate term; `train` (and `validation`) its rows.
SelectionResult select_effects(const sim::AugmentedModel& catalogue, const DecimatedRows& train, const DecimatedRows* validation,
                               const SelectionSettings& settings, const std::function<void(const std::string&)>& progress);

}  // namespace jacobid::diagnose
