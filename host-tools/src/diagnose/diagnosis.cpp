// SPDX-License-Identifier: MIT
#include "diagnose/diagnosis.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "diagnose/blocked_grams.hpp"
#include "diagnose/decimated_rows.hpp"
#include "diagnose/heldout.hpp"
#include "diagnose/statistics.hpp"
#include "identify/pipeline/segmented_pipeline.hpp"
#include "identify/validation/validation.hpp"
#include "sim/augmented_model.hpp"

namespace jacobid::diagnose {
namespace {

using Clock = std::chrono::steady_clock;

// Catalogue columns of a model's parameters (matched by name).
std::vector<int> catalogue_columns(const robot::RobotModel& model, const DecimatedRows& rows) {
    std::vector<int> cols;
    for (const auto& name : model.parameter_names()) {
        const auto it = std::find(rows.names.begin(), rows.names.end(), name);
        if (it == rows.names.end()) throw std::logic_error("diagnose: column " + name + " missing from the catalogue");
        cols.push_back(static_cast<int>(it - rows.names.begin()));
    }
    return cols;
}

// What every log goes through: the caller's settings for one log; for several, the plan resolved on the
// longest and imposed on all (plan_segments), the Coulomb columns' velocity included.
struct LogsPlan {
    identify::PipelineSettings pipeline;
    std::optional<identify::SegmentPlan> several;
};

LogsPlan plan_logs(const robot::RobotModel& model, const std::vector<identify::LogColumns>& logs, const identify::PipelineSettings& settings) {
    LogsPlan p;
    p.pipeline = settings;
    if (logs.size() < 2) return p;
    p.several = identify::plan_segments(logs, settings, {"--in", "log"});
    identify::PipelineSettings& fixed = p.several->fixed;
    if (fixed.coulomb_velocity_ratios.empty()) {
        fixed.coulomb_velocity_ratios = identify::coulomb_velocity_ratios(&model, logs[p.several->reference], fixed, p.several->info);
    }
    p.pipeline = fixed;
    return p;
}

// The identification of `model` on `logs` (torque channel read `delay` later), measured against the data.
ModelSnapshot measure(const robot::RobotModel& model, const std::vector<identify::LogColumns>& logs, const LogsPlan& plan, double delay,
                      const DecimatedRows& train, const DecimatedRows* validation, const std::vector<identify::LogColumns>& horizon_logs,
                      const DiagnoseSettings& s, const std::vector<double>& weight2) {
    ModelSnapshot m;
    identify::PipelineSettings ps = plan.pipeline;
    ps.progress = false;
    ps.residual_lags = 0;  // solved with the pooled std below: no lagged products needed
    if (plan.several) {
        identify::SegmentPlan quiet = *plan.several;
        quiet.fixed = ps;
        quiet.fixed.require_own_equations = false;  // every log's rows are in `train`: every log's equations here
        m.solution = identify::solve_least_squares(identify::run_segmented_pipeline(model, logs, quiet, delay, ps.threads).merged.factors,
                                                   model.parameter_names());
    } else {
        const ShiftedTorques shifted = shift_torques(logs.front(), delay);
        m.solution = identify::solve_least_squares(identify::run_pipeline(model, shifted.log, ps).factors, model.parameter_names());
    }
    m.residual_rms = m.solution.joint_residual_rms;
    const Eigen::VectorXd x = m.solution.x.unaryExpr([](double v) { return std::isnan(v) ? 0.0 : v; });

    const std::vector<int> cols = catalogue_columns(model, train);
    const auto y = train.shifted_ys(delay);
    for (int j = 0; j < train.joints(); ++j) {
        m.residual.push_back(y[static_cast<std::size_t>(j)] - train.w[static_cast<std::size_t>(j)](Eigen::all, cols) * x);
        m.analysis.push_back(analyse_residual(m.residual.back(), train.state[static_cast<std::size_t>(j)], train.t));
    }
    BlockedGrams grams(train, s.selection.folds);
    grams.set_y(y);
    std::unique_ptr<BlockedGrams> vgrams;
    if (validation) {
        vgrams = std::make_unique<BlockedGrams>(*validation, 1);
        vgrams->set_y(validation->shifted_ys(delay));
    }
    const HeldOut heldout(grams, vgrams.get(), weight2);
    for (int j = 0; j < train.joints(); ++j) m.heldout_rms.push_back(heldout.rms(cols, j));
    m.heldout_weighted = heldout.rms(cols);

    const identify::PipelineSettings horizon_settings = identify::validation_settings(ps, train.info);
    std::vector<HorizonResult> horizons;
    for (const identify::LogColumns& horizon_log : horizon_logs) {
        identify::PipelineInfo info = identify::plan_pipeline(horizon_log, horizon_settings);
        const identify::StateEstimates states = identify::estimate_states(horizon_log, horizon_settings, info);
        horizons.push_back(simulate_horizons(model, x, horizon_log, states, delay, s.horizon));
    }
    m.horizon = pooled_horizons(horizons);
    return m;
}

// Effect values and honest standard deviations: the weighted LS of the final model on the identification
// rows, covariance scaled by n / n_eff of its residual.
std::vector<EffectEstimate> effect_estimates(const Diagnosis& d, const sim::AugmentedModel& augmented, const DecimatedRows& train,
                                             const std::vector<double>& weight2) {
    const std::vector<int> cols = catalogue_columns(augmented, train);
    BlockedGrams grams(train, 1);
    grams.set_y(train.shifted_ys(d.delay));
    const SubsetFit fit = solve_subset(grams.sum(cols, weight2, -1, false));
    double rows = 0.0, n_eff = 0.0, wrss = 0.0;
    for (int j = 0; j < train.joints(); ++j) {
        const auto& r = d.after.residual[static_cast<std::size_t>(j)];
        rows += static_cast<double>(r.size());
        n_eff += effective_sample_size(r);
    }
    wrss = fit.ok ? fit.rss : 0.0;
    const double sigma2 = wrss / std::max(1.0, rows - static_cast<double>(cols.size()));
    std::vector<EffectEstimate> effects;
    for (const auto& accepted : d.selection.accepted) {
        EffectEstimate e;
        e.term = accepted.term;
        e.test = accepted;
        if (accepted.term.kind == sim::EffectKind::TorqueDelay) {
            e.value = accepted.delay;
            e.std = accepted.std;
        } else if (fit.ok) {
            std::size_t t = 0;
            while (t < augmented.terms().size() && !augmented.terms()[t].same_as(e.term)) ++t;
            const Eigen::Index first = augmented.term_column(t), k = e.term.column_count();
            e.coefficients = fit.x.segment(first, k);
            const Eigen::MatrixXd cov = sigma2 * (rows / n_eff) * fit.inverse.block(first, first, k, k);
            e.value = sim::term_value(e.term, e.coefficients);
            e.std = sim::term_value_std(e.term, e.coefficients, cov);
        }
        effects.push_back(e);
    }
    return effects;
}

// Why no effect was named: no candidate could be tested, or the strongest one and what it lacked, with whether the
// residual left is noise (white to within the residual analysis's bound) or structure no candidate explains.
std::string verdict_without_effects(const Diagnosis& d, const DiagnoseSettings& s) {
    const auto& step = d.selection.steps.front();
    if (step.top.empty()) return "no effect named: no candidate could be tested";
    const CandidateTest& b = step.top.front();
    std::string floor;
    for (std::size_t j = 0; j < d.before.residual_rms.size(); ++j) {
        floor += fmt::format("{}{:.3g}", j ? " / " : "", d.before.residual_rms[j]);
    }
    // "To the noise floor" only when what is left looks like noise: every joint's residual close to
    // white (effective sample size at least a fifth of its rows, the residual analysis's own bound for
    // "strongly correlated"). Otherwise the structure is there and no candidate of the catalogue names it.
    std::string structured;
    for (std::size_t j = 0; j < d.before.analysis.size(); ++j) {
        const JointResidualAnalysis& a = d.before.analysis[j];
        // A residual that is exactly zero (NaN effective size) has no structure either.
        if (!strongly_correlated(a, static_cast<std::size_t>(d.before.residual[j].size())) || a.rms == 0.0) continue;
        std::string where;
        if (!a.velocity.empty()) {
            const auto worst = std::max_element(a.velocity.begin(), a.velocity.end(),
                                                [](const Bin& x, const Bin& y) { return std::abs(x.mean) < std::abs(y.mean); });
            where = fmt::format(", largest mean residual {:+.3g} N.m at {}", worst->mean, worst->label);
        }
        structured += fmt::format("{}joint {} (rho_1 {:.2f}, effective sample size {:.0f} of {} rows{})", structured.empty() ? "" : "; ", j + 1,
                                  a.autocorrelation.empty() ? 0.0 : a.autocorrelation.front(), a.n_eff, d.before.residual[j].size(), where);
    }
    const std::string what =
        structured.empty() ? fmt::format("the data are explained by the nominal model to the noise floor (residual RMS {} N.m per joint, "
                                         "white to within the residual analysis's bound)",
                                         floor)
                           : fmt::format("structure is left in the residual that no candidate explains (residual RMS {} N.m per joint): {}",
                                         floor, structured);
    return fmt::format(
        "no effect named: {}. Strongest candidate {} (estimate {:.3g} +- {} {}): {}; held-out error {:+.1f} % ({} needed)", what,
        b.label(), b.value, std::isfinite(b.std) ? fmt::format("{:.2g}", b.std) : "n/a", sim::effect_unit(b.term.kind),
        b.significant ? "significant" : fmt::format("not significant (adjusted p = {:.2g} >= {:g})", b.adjusted_p, s.selection.alpha),
        -100.0 * b.gain, fmt::format("-{:g} %", 100.0 * s.selection.min_gain));
}

}  // namespace

Diagnosis run_diagnosis(const robot::RobotModel& nominal, const sim::EffectContext& context, const identify::LogColumns& log,
                        const identify::LogColumns* validation, const DiagnoseSettings& s, const Progress& progress) {
    return run_diagnosis(nominal, context, std::vector<identify::LogColumns>{log}, validation, s, progress);
}

Diagnosis run_diagnosis(const robot::RobotModel& nominal, const sim::EffectContext& context, const std::vector<identify::LogColumns>& logs,
                        const identify::LogColumns* validation, const DiagnoseSettings& s, const Progress& progress) {
    if (logs.empty()) throw std::logic_error("diagnose: no log");
    const auto start = Clock::now();
    auto say = [&](const std::string& text) {
        if (progress) progress(fmt::format("[{:5.1f} s] {}", std::chrono::duration<double>(Clock::now() - start).count(), text));
    };
    Diagnosis d;
    std::size_t samples = 0;
    for (const identify::LogColumns& log : logs) {
        d.log_sources.push_back(log.source);
        d.log_source += (d.log_source.empty() ? "" : ", ") + log.source;
        samples += log.samples();
    }
    d.validation_source = validation ? validation->source : "";
    d.model_name = nominal.model_name();

    const Catalogue catalogue = candidate_catalogue(context, s.catalogue);
    d.notes = catalogue.notes;
    const sim::AugmentedModel cat(nominal, context, catalogue.terms);
    d.catalogue_columns = static_cast<std::size_t>(cat.parameter_count());
    say(fmt::format("regressor of the nominal model ({} parameters) and {} candidate terms ({} columns) on {} samples of {}",
                    nominal.parameter_count(), catalogue.terms.size(), cat.parameter_count() - nominal.parameter_count(), samples,
                    d.log_source));
    const LogsPlan plan = plan_logs(cat, logs, s.pipeline);
    const DecimatedRows train =
        plan.several ? stacked_decimated_rows(cat, logs, plan.pipeline, plan.several->info) : decimated_rows(cat, logs.front(), s.pipeline);
    d.info = train.info;
    d.state = train.state;
    d.t = train.t;
    std::unique_ptr<DecimatedRows> vrows;
    if (validation) {
        say(fmt::format("same regressor on the validation log {}", validation->source));
        vrows = std::make_unique<DecimatedRows>(decimated_rows(cat, *validation, identify::validation_settings(plan.pipeline, train.info)));
    }
    say(fmt::format("{} decimated rows per joint (decimation {}, F_p {:.3g} Hz); stepwise selection", train.rows(), train.info.decimation,
                    train.info.decimation_cutoff));
    d.selection = select_effects(cat, train, vrows.get(), s.selection, [&](const std::string& m) { say(m); });
    d.delay = d.selection.delay;
    if (!d.selection.unexcited.empty()) {
        std::string names;
        for (const auto& n : d.selection.unexcited) names += (names.empty() ? "" : ", ") + n;
        d.notes.push_back(fmt::format("{} nominal parameter{} not excited by this log, left out of the search: {}", d.selection.unexcited.size(),
                                      d.selection.unexcited.size() == 1 ? "" : "s", names));
    }
    std::vector<double> weight2;
    for (double sj : d.selection.joint_sigma) weight2.push_back(1.0 / (sj * sj));

    say("re-identifying with the augmented model; short-horizon simulations before and after");
    const std::vector<identify::LogColumns> horizon_logs = validation ? std::vector<identify::LogColumns>{*validation} : logs;
    d.before = measure(nominal, logs, plan, 0.0, train, vrows.get(), horizon_logs, s, weight2);
    const sim::AugmentedModel augmented(nominal, context, d.selection.terms);
    d.after = measure(augmented, logs, plan, d.delay, train, vrows.get(), horizon_logs, s, weight2);

    d.effects = effect_estimates(d, augmented, train, weight2);
    d.verdict = d.effects.empty() ? verdict_without_effects(d, s) : fmt::format("{} effect{} named", d.effects.size(), d.effects.size() > 1 ? "s" : "");
    d.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    say(fmt::format("done: {}", d.verdict));
    return d;
}

}  // namespace jacobid::diagnose
