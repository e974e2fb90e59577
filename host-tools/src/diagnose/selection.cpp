// SPDX-License-Identifier: MIT
#include "diagnose/selection.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/errors.hpp"
#include "diagnose/blocked_grams.hpp"
#include "diagnose/heldout.hpp"
#include "diagnose/statistics.hpp"

namespace jacobid::diagnose {

std::string CandidateTest::label() const {
    if (term.kind == sim::EffectKind::TorqueDelay) return fmt::format("torque_delay {:.2f} ms", 1e3 * delay);
    return term.label();
}

namespace {

std::vector<int> with(std::vector<int> columns, int first, int count) {
    for (int c = 0; c < count; ++c) columns.push_back(first + c);
    return columns;
}

// Per-joint residuals of the weighted fit over `columns` on all training rows.
std::vector<Eigen::VectorXd> residuals(const DecimatedRows& rows, const std::vector<Eigen::VectorXd>& y, const std::vector<int>& columns,
                                       const Eigen::VectorXd& x) {
    // An empty x is a failed solve: a logic error here, never an out-of-bounds product.
    if (x.size() != static_cast<Eigen::Index>(columns.size())) throw std::logic_error("diagnose: residuals of an unsolved column set");
    std::vector<Eigen::VectorXd> r;
    for (int j = 0; j < rows.joints(); ++j) r.push_back(y[static_cast<std::size_t>(j)] - rows.w[static_cast<std::size_t>(j)](Eigen::all, columns) * x);
    return r;
}

// The first `count` catalogue columns kept in order while the kept set stays solvable under `weight2`.
std::vector<int> identifiable_columns(const BlockedGrams& grams, int count, const std::vector<double>& weight2) {
    std::vector<int> all(static_cast<std::size_t>(count));
    for (int c = 0; c < count; ++c) all[static_cast<std::size_t>(c)] = c;
    const GramSums g = grams.sum(all, weight2, -1, false);
    std::vector<int> kept;
    for (int c = 0; c < count; ++c) {
        kept.push_back(c);
        const bool excited = g.G(c, c) > 1e-12 * g.G.diagonal().maxCoeff();
        if (excited && solve_subset(grams.sum(kept, weight2, -1, false)).ok) continue;
        kept.pop_back();
    }
    return kept;
}

bool same_slot(const sim::EffectTerm& a, const sim::EffectTerm& b) {
    if (a.kind != b.kind || a.joint != b.joint) return false;
    return a.kind != sim::EffectKind::Cogging || a.order == b.order;
}

// Nominal columns that the data excite: a joint that does not move leaves its columns zero, and a log that
// moves one joint at a time leaves combinations of the others' columns collinear. Columns are kept in
// model order while the kept set stays solvable (a maximal identifiable subset, as identify's pivoted QR
// keeps one); the others are named in result.unexcited. Chosen unweighted first (for the joint weights,
// result.joint_sigma), then again with the weights the search uses: reweighting a nearly collinear set can
// make it singular (a UR10e joint-at-a-time log does), and every later fit builds on this set.
// Returns the kept columns; `weight2` gets the row weights 1 / sigma_j^2, fixed for the whole selection.
std::vector<int> excited_nominal_columns(const sim::AugmentedModel& catalogue, const BlockedGrams& grams, const DecimatedRows& train,
                                         SelectionResult& result, std::vector<double>& weight2) {
    const int c0 = catalogue.nominal().parameter_count();
    std::vector<int> model = identifiable_columns(grams, c0, {});
    if (model.empty()) throw InputError("diagnose: no nominal parameter is excited by this log (does any joint move?)");
    const SubsetFit f = solve_subset(grams.sum(model, {}, -1, false));
    for (const auto& rj : residuals(train, train.y, model, f.x)) {
        result.joint_sigma.push_back(std::max(1e-12, std::sqrt(rj.squaredNorm() / static_cast<double>(rj.size()))));
    }
    for (double sj : result.joint_sigma) weight2.push_back(1.0 / (sj * sj));
    model = identifiable_columns(grams, c0, weight2);
    if (model.empty()) throw InputError("diagnose: the nominal regressor is singular on this log once its joints are weighted");
    for (int c = 0; c < c0; ++c) {
        if (std::find(model.begin(), model.end(), c) == model.end())
            result.unexcited.push_back(catalogue.nominal().parameter_names()[static_cast<std::size_t>(c)]);
    }
    return model;
}

// One step's evidence scale: the residual rows, their effective number (serial correlation) and the ratio,
// by which a chi-square of correlated residuals is deflated.
struct StepEvidence {
    double rows = 0.0, n_eff = 0.0;
    double inflation() const { return rows / n_eff; }

    // Fills t's chi2, p, score and held-out gain from the fits without (rss0) and with (rss1, k1 columns) the
    // candidate; returns the residual variance with it.
    double judge(CandidateTest& t, double rss0, double rss1, double k1) const {
        const double sigma2 = rss1 / std::max(1.0, rows - k1);
        // No residual left to scale by (rss1 = 0, or no effective sample) is no evidence either way: chi2 0.
        const double scale = sigma2 * inflation();
        t.chi2 = scale > 0.0 && std::isfinite(scale) ? std::max(0.0, rss0 - rss1) / scale : 0.0;
        if (!std::isfinite(t.chi2)) t.chi2 = 0.0;
        t.p_value = chi_square_survival(t.chi2, t.dof);
        t.score = t.chi2 - t.dof * std::log(n_eff);
        t.gain = t.heldout_before > 0 ? 1.0 - t.heldout_after / t.heldout_before : 0.0;
        return sigma2;
    }
};

// What one step of the forward selection works with.
struct StepInputs {
    const sim::AugmentedModel& catalogue;
    BlockedGrams& grams;
    BlockedGrams* vgrams;
    const DecimatedRows& train;
    const DecimatedRows* validation;
    const HeldOut& heldout;
    const std::vector<double>& weight2;
    const std::vector<int>& model;
    const SubsetFit& fit0;
    const SelectionStep& step;
    const StepEvidence& evidence;
};

// Every catalogue term not yet in the model, added to it and tested (`skipped`: the unsolvable ones, on the
// first step only).
void test_columns(const StepInputs& in, const std::vector<bool>& used, const SelectionResult& result, bool first_step, std::vector<std::string>& skipped,
                  std::vector<CandidateTest>& tests) {
    for (std::size_t i = 0; i < in.catalogue.terms().size(); ++i) {
        const sim::EffectTerm& term = in.catalogue.terms()[i];
        if (used[i]) continue;
        bool taken = false;
        for (const auto& a : result.terms) taken = taken || (same_slot(a, term) && !(term.kind == sim::EffectKind::Cogging));
        if (taken) continue;
        const std::vector<int> cols = with(in.model, in.catalogue.term_column(i), term.column_count());
        const SubsetFit f = solve_subset(in.grams.sum(cols, in.weight2, -1, false));
        if (!f.ok) {
            if (first_step) skipped.push_back(term.label());
            continue;
        }
        CandidateTest t;
        t.term = term;
        t.dof = term.column_count();
        t.heldout_before = in.step.heldout;
        t.heldout_after = in.heldout.rms(cols);
        const double sigma2 = in.evidence.judge(t, in.fit0.rss, f.rss, static_cast<double>(cols.size()));
        const Eigen::Index k = term.column_count();
        const Eigen::VectorXd coef = f.x.tail(k);
        const Eigen::MatrixXd cov = sigma2 * in.evidence.inflation() * f.inverse.bottomRightCorner(k, k);
        t.value = sim::term_value(term, coef);
        t.std = sim::term_value_std(term, coef, cov);
        tests.push_back(t);
    }
}

// The torque delay as a candidate: a grid of one sample within +-max_delay around the current delay, then a
// parabolic refinement around the best point; returns the grid's size (each point is a test).
std::size_t test_delay(const StepInputs& in, double max_delay, double delay, std::vector<CandidateTest>& tests) {
    const double h = in.train.sample_period;
    const int half = std::max(1, static_cast<int>(std::lround(max_delay / h)));
    std::vector<double> rss;
    for (int i = -half; i <= half; ++i) {
        in.grams.set_y(in.train.shifted_ys(delay + i * h));
        const SubsetFit f = solve_subset(in.grams.sum(in.model, in.weight2, -1, false));
        rss.push_back(f.ok ? f.rss : INFINITY);
    }
    const auto best = static_cast<int>(std::min_element(rss.begin(), rss.end()) - rss.begin());
    double d = (best - half) * h, curvature = 0.0;
    if (best > 0 && best + 1 < static_cast<int>(rss.size())) {
        const double rm = rss[static_cast<std::size_t>(best - 1)], rc = rss[static_cast<std::size_t>(best)], rp = rss[static_cast<std::size_t>(best + 1)];
        const double den = rm - 2.0 * rc + rp;
        if (den > 0.0) {
            d += 0.5 * h * (rm - rp) / den;
            curvature = den / (h * h);
        }
    }
    CandidateTest t;
    t.term.kind = sim::EffectKind::TorqueDelay;
    t.dof = 1;
    t.delay = delay + d;
    in.grams.set_y(in.train.shifted_ys(t.delay));
    if (in.vgrams) in.vgrams->set_y(in.validation->shifted_ys(t.delay));
    const SubsetFit f = solve_subset(in.grams.sum(in.model, in.weight2, -1, false));
    t.heldout_before = in.step.heldout;
    t.heldout_after = in.heldout.rms(in.model);
    const double sigma2 = in.evidence.judge(t, in.fit0.rss, f.ok ? f.rss : in.fit0.rss, static_cast<double>(in.model.size() + 1));
    t.value = t.delay;
    t.std = curvature > 0.0 ? std::sqrt(2.0 * sigma2 * in.evidence.inflation() / curvature) : INFINITY;
    tests.push_back(t);
    in.grams.set_y(in.train.shifted_ys(delay));
    if (in.vgrams) in.vgrams->set_y(in.validation->shifted_ys(delay));
    return rss.size();
}

std::string describe_step(int step, const SelectionStep& st, const std::vector<CandidateTest>& tests) {
    return fmt::format("step {}: {} candidates, n_eff {:.0f} of {:.0f} rows, best {} (chi2 {:.1f}, adjusted p {:.2g}, held-out {:+.1f} %){}", step + 1,
                       st.tested, st.n_eff, st.rows, tests.empty() ? "-" : tests.front().label(), tests.empty() ? 0.0 : tests.front().chi2,
                       tests.empty() ? 1.0 : tests.front().adjusted_p, tests.empty() ? 0.0 : -100.0 * tests.front().gain,
                       st.accepted ? ": accepted" : ": nothing passes");
}

}  // namespace

SelectionResult select_effects(const sim::AugmentedModel& catalogue, const DecimatedRows& train, const DecimatedRows* validation,
                               const SelectionSettings& s, const std::function<void(const std::string&)>& progress) {
    SelectionResult result;
    BlockedGrams grams(train, s.folds);
    std::unique_ptr<BlockedGrams> vgrams = validation ? std::make_unique<BlockedGrams>(*validation, 1) : nullptr;
    result.heldout_kind = validation ? "validation log" : fmt::format("{}-fold blocked cross-validation", grams.blocks());
    std::vector<double> weight2;
    std::vector<int> model = excited_nominal_columns(catalogue, grams, train, result, weight2);
    const HeldOut heldout(grams, vgrams.get(), weight2);

    std::vector<bool> used(catalogue.terms().size(), false);
    bool delay_used = !s.search_delay;
    for (int step = 0; step < s.max_effects; ++step) {
        SelectionStep st;
        const SubsetFit fit0 = solve_subset(grams.sum(model, weight2, -1, false));
        StepEvidence evidence;
        for (const Eigen::VectorXd& r : residuals(train, train.shifted_ys(result.delay), model, fit0.x)) {
            evidence.rows += static_cast<double>(r.size());
            evidence.n_eff += effective_sample_size(r);
        }
        st.rows = evidence.rows;
        st.n_eff = evidence.n_eff;
        st.heldout = heldout.rms(model);
        const StepInputs in{catalogue, grams, vgrams.get(), train, validation, heldout, weight2, model, fit0, st, evidence};
        std::vector<CandidateTest> tests;
        test_columns(in, used, result, step == 0, result.skipped, tests);
        const std::size_t delay_grid = delay_used ? 0 : test_delay(in, s.max_delay, result.delay, tests);

        st.tested = tests.size() + (delay_grid > 0 ? delay_grid - 1 : 0);
        for (auto& t : tests) {
            t.adjusted_p = std::min(1.0, t.p_value * static_cast<double>(st.tested));
            t.significant = t.adjusted_p < s.alpha;
            t.generalizes = std::isfinite(t.heldout_after) && t.gain >= s.min_gain;
        }
        // Accepted candidates first, then by score.
        std::sort(tests.begin(), tests.end(), [](const CandidateTest& a, const CandidateTest& b) {
            if (a.accepted() != b.accepted()) return a.accepted();
            return a.score > b.score;
        });
        st.top.assign(tests.begin(), tests.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(5, tests.size())));
        st.accepted = !tests.empty() && tests.front().accepted();
        if (progress) progress(describe_step(step, st, tests));
        result.steps.push_back(st);
        if (!st.accepted) break;
        const CandidateTest& a = tests.front();
        result.accepted.push_back(a);
        if (a.term.kind == sim::EffectKind::TorqueDelay) {
            result.delay = a.delay;
            delay_used = true;
            grams.set_y(train.shifted_ys(result.delay));
            if (vgrams) vgrams->set_y(validation->shifted_ys(result.delay));
        } else {
            for (std::size_t i = 0; i < catalogue.terms().size(); ++i) {
                if (catalogue.terms()[i].same_as(a.term)) {
                    used[i] = true;
                    model = with(model, catalogue.term_column(i), a.term.column_count());
                }
            }
            result.terms.push_back(a.term);
        }
    }
    return result;
}

}  // namespace jacobid::diagnose
