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

}  // namespace

SelectionResult select_effects(const sim::AugmentedModel& catalogue, const DecimatedRows& train, const DecimatedRows* validation,
                               const SelectionSettings& s, const std::function<void(const std::string&)>& progress) {
    SelectionResult result;
    const int joints = train.joints();
    BlockedGrams grams(train, s.folds);
    std::unique_ptr<BlockedGrams> vgrams = validation ? std::make_unique<BlockedGrams>(*validation, 1) : nullptr;
    result.heldout_kind = validation ? "validation log" : fmt::format("{}-fold blocked cross-validation", grams.blocks());

    // Nominal columns that the data excite: a joint that does not move leaves its columns zero, and a log that
    // moves one joint at a time leaves combinations of the others' columns collinear. Columns are kept in
    // model order while the kept set stays solvable (a maximal identifiable subset, as identify's pivoted QR
    // keeps one); the others are named in a note. Chosen unweighted first (for the joint weights), then
    // again with the weights the search uses: reweighting a nearly collinear set can make it singular
    // (a UR10e joint-at-a-time log does), and every later fit builds on this set.
    const int c0 = catalogue.nominal().parameter_count();
    std::vector<int> model = identifiable_columns(grams, c0, {});
    if (model.empty()) throw InputError("diagnose: no nominal parameter is excited by this log (does any joint move?)");
    // Row weights 1 / sigma_j from the nominal fit, fixed for the whole selection.
    {
        const SubsetFit f = solve_subset(grams.sum(model, {}, -1, false));
        const auto r = residuals(train, train.y, model, f.x);
        for (const auto& rj : r) result.joint_sigma.push_back(std::max(1e-12, std::sqrt(rj.squaredNorm() / static_cast<double>(rj.size()))));
    }
    std::vector<double> weight2;
    for (double sj : result.joint_sigma) weight2.push_back(1.0 / (sj * sj));
    model = identifiable_columns(grams, c0, weight2);
    if (model.empty()) throw InputError("diagnose: the nominal regressor is singular on this log once its joints are weighted");
    for (int c = 0; c < c0; ++c) {
        if (std::find(model.begin(), model.end(), c) == model.end())
            result.unexcited.push_back(catalogue.nominal().parameter_names()[static_cast<std::size_t>(c)]);
    }
    const HeldOut heldout(grams, vgrams.get(), weight2);

    std::vector<bool> used(catalogue.terms().size(), false);
    bool delay_used = !s.search_delay;
    for (int step = 0; step < s.max_effects; ++step) {
        SelectionStep st;
        const std::vector<Eigen::VectorXd> y_now = train.shifted_ys(result.delay);
        const GramSums base = grams.sum(model, weight2, -1, false);
        const SubsetFit fit0 = solve_subset(base);
        const auto r0 = residuals(train, y_now, model, fit0.x);
        for (int j = 0; j < joints; ++j) {
            st.rows += static_cast<double>(r0[static_cast<std::size_t>(j)].size());
            st.n_eff += effective_sample_size(r0[static_cast<std::size_t>(j)]);
        }
        const double inflation = st.rows / st.n_eff;
        st.heldout = heldout.rms(model);
        std::vector<CandidateTest> tests;

        auto judge = [&](CandidateTest& t, double rss0, double rss1, double k1) {
            const double sigma2 = rss1 / std::max(1.0, st.rows - k1);
            // No residual left to scale by (rss1 = 0, or no effective sample) is no evidence either way: chi2 0.
            const double scale = sigma2 * inflation;
            t.chi2 = scale > 0.0 && std::isfinite(scale) ? std::max(0.0, rss0 - rss1) / scale : 0.0;
            if (!std::isfinite(t.chi2)) t.chi2 = 0.0;
            t.p_value = chi_square_survival(t.chi2, t.dof);
            t.score = t.chi2 - t.dof * std::log(st.n_eff);
            t.gain = t.heldout_before > 0 ? 1.0 - t.heldout_after / t.heldout_before : 0.0;
            return sigma2;
        };

        // Column candidates.
        for (std::size_t i = 0; i < catalogue.terms().size(); ++i) {
            const sim::EffectTerm& term = catalogue.terms()[i];
            if (used[i]) continue;
            bool taken = false;
            for (const auto& a : result.terms) taken = taken || (same_slot(a, term) && !(term.kind == sim::EffectKind::Cogging));
            if (taken) continue;
            const std::vector<int> cols = with(model, catalogue.term_column(i), term.column_count());
            const SubsetFit f = solve_subset(grams.sum(cols, weight2, -1, false));
            if (!f.ok) {
                if (step == 0) result.skipped.push_back(term.label());
                continue;
            }
            CandidateTest t;
            t.term = term;
            t.dof = term.column_count();
            t.heldout_before = st.heldout;
            t.heldout_after = heldout.rms(cols);
            const double sigma2 = judge(t, fit0.rss, f.rss, static_cast<double>(cols.size()));
            const Eigen::Index k = term.column_count();
            const Eigen::VectorXd coef = f.x.tail(k);
            const Eigen::MatrixXd cov = sigma2 * inflation * f.inverse.bottomRightCorner(k, k);
            t.value = sim::term_value(term, coef);
            t.std = sim::term_value_std(term, coef, cov);
            tests.push_back(t);
        }
        // The torque delay: grid of one sample, parabolic refinement around the best point.
        std::size_t delay_grid = 0;
        if (!delay_used) {
            const double h = train.sample_period;
            const int half = std::max(1, static_cast<int>(std::lround(s.max_delay / h)));
            std::vector<double> rss;
            for (int i = -half; i <= half; ++i) {
                grams.set_y(train.shifted_ys(result.delay + i * h));
                const SubsetFit f = solve_subset(grams.sum(model, weight2, -1, false));
                rss.push_back(f.ok ? f.rss : INFINITY);
            }
            delay_grid = rss.size();
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
            t.delay = result.delay + d;
            grams.set_y(train.shifted_ys(t.delay));
            if (vgrams) vgrams->set_y(validation->shifted_ys(t.delay));
            const SubsetFit f = solve_subset(grams.sum(model, weight2, -1, false));
            t.heldout_before = st.heldout;
            t.heldout_after = heldout.rms(model);
            const double sigma2 = judge(t, fit0.rss, f.ok ? f.rss : fit0.rss, static_cast<double>(model.size() + 1));
            t.value = t.delay;
            t.std = curvature > 0.0 ? std::sqrt(2.0 * sigma2 * inflation / curvature) : INFINITY;
            tests.push_back(t);
            grams.set_y(y_now);
            if (vgrams) vgrams->set_y(validation->shifted_ys(result.delay));
        }

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
        if (progress) {
            progress(fmt::format("step {}: {} candidates, n_eff {:.0f} of {:.0f} rows, best {} (chi2 {:.1f}, adjusted p {:.2g}, held-out {:+.1f} %){}",
                                 step + 1, st.tested, st.n_eff, st.rows, tests.empty() ? "-" : tests.front().label(),
                                 tests.empty() ? 0.0 : tests.front().chi2, tests.empty() ? 1.0 : tests.front().adjusted_p,
                                 tests.empty() ? 0.0 : -100.0 * tests.front().gain, st.accepted ? ": accepted" : ": nothing passes"));
        }
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
