// SPDX-License-Identifier: MIT
#include "identify/report/report.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "identify/physical/physical_identification.hpp"
#include "plot/gnuplot.hpp"

namespace jacobid::identify {
namespace {

std::string num(double v, const char* spec = "{:.4g}") { return std::isnan(v) ? std::string("-") : fmt::format(fmt::runtime(spec), v); }

std::string method_title(const MethodResult& r) { return r.info.method == Method::Jacobi ? "Jacobi" : "Butterworth"; }

std::string combination(const Unidentifiable& u, const std::vector<std::string>& names) {
    std::string s;
    for (std::size_t i = 0; i < u.parameters.size(); ++i) {
        const double a = u.coefficients[i];
        s += fmt::format("{}{:.3g} {}", i == 0 ? (a < 0 ? "-" : "") : (a < 0 ? " - " : " + "), std::abs(a), names[static_cast<std::size_t>(u.parameters[i])]);
    }
    return s;
}

std::string settings_line(const PipelineInfo& i) {
    std::string s = fmt::format("bandwidth {:.3g} Hz{}", i.bandwidth, i.bandwidth_estimated ? " (estimated)" : "");
    if (i.method == Method::Jacobi) {
        s += fmt::format(", Jacobi windows {:.4g} s (velocity, cutoff {:.3g} Hz) / {:.4g} s (acceleration, cutoff {:.3g} Hz)", i.velocity_window,
                         i.velocity_cutoff, i.acceleration_window, i.acceleration_cutoff);
    } else {
        s += fmt::format(", Butterworth prefilter {:.3g} Hz + central Euler differences", i.prefilter_cutoff);
    }
    s += fmt::format(", F_p {:.3g} Hz, decimation {}", i.decimation_cutoff, i.decimation);
    if (!i.coulomb_velocity_cutoffs.empty()) {
        // Per joint, the velocity inside the Coulomb sign function (docs/method.md, "Coulomb columns").
        std::string cutoffs;
        for (double f : i.coulomb_velocity_cutoffs) cutoffs += fmt::format("{}{:.3g}", cutoffs.empty() ? "" : " ", f);
        s += fmt::format(", Coulomb velocity {} Hz", cutoffs);
    }
    return s;
}

// One line on how sigma_X was computed, so that %sigma_r can be read for what it is.
std::string describe_std(const MethodResult& r) {
    const LsSolution& sol = r.solution;
    if (r.estimator && r.estimator->estimator == Estimator::Iv) {
        return fmt::format("{} IV, std: the IV sandwich s^2 (Z'SW)^-1 Z'SZ (W'SZ)^-1, rows independent",
                           sol.weighted ? "weighted (1 / sigma_j of the LS per joint)" : "unweighted");
    }
    std::string s = fmt::format("{} LS, std ", sol.weighted ? "weighted (1 / sigma_j per joint)" : "ordinary");
    if (sol.std_method == StdMethod::Pooled) return s + "pooled: sigma_rho^2 (W^T W)^-1, one residual variance, rows independent";
    s += fmt::format("joint-hac: per-joint residual variances x long-run factors (Bartlett, {} lags) in a sandwich;", sol.std_lags);
    for (std::size_t j = 0; j < sol.joint_sigma.size(); ++j) {
        s += fmt::format(" joint {} sigma {:.3g}, factor {:.2f}, lag-1 correlation {};", j + 1, sol.joint_sigma[j], sol.joint_long_run_factors[j],
                         num(sol.joint_lag1_correlation[j], "{:.2f}"));
    }
    s.pop_back();
    return s;
}

// The iterated estimator's line: which, from what, how it ended, and what its std is.
std::string describe_estimator(const EstimatorRun& run) {
    const bool iv = run.estimator == Estimator::Iv;
    return fmt::format("estimator {} ({}), from the WLS/OLS estimate: {} iteration{}, {} (last relative change of X {:.2g}, tolerance {:g} or at most "
                       "{} iterations)",
                       to_string(run.estimator), iv ? "IDIM-IV, instruments from the closed-loop simulation of the identified model" : "DIDIM, regressor of the closed-loop simulation of the identified model",
                       run.iterations, run.iterations == 1 ? "" : "s", run.converged ? "converged" : "NOT converged",
                       run.changes.empty() ? 0.0 : run.changes.back(), run.tolerance, run.max_iterations);
}

}  // namespace

std::vector<std::string> identifiability_warnings(const MethodResult& r, const std::vector<std::string>& joint_names) {
    std::vector<std::string> w;
    for (std::size_t j = 0; j < r.info.joint_moves.size(); ++j) {
        if (!r.info.joint_moves[j]) {
            w.push_back(fmt::format("joint {} ({}) does not move (position range {:.3g} rad): parameters excited only by its motion cannot be identified",
                                    j + 1, j < joint_names.size() ? joint_names[j] : "?", r.info.joint_range[j]));
        }
    }
    for (const auto& u : r.solution.unidentifiable) {
        if (u.zero_column) {
            w.push_back(fmt::format("{} cannot be identified: its regressor column is zero on this trajectory",
                                    r.solution.names[static_cast<std::size_t>(u.parameters.front())]));
        } else {
            w.push_back(fmt::format("rank deficiency: W a = 0 for a = {} (only combinations of these parameters are identifiable)",
                                    combination(u, r.solution.names)));
        }
    }
    for (std::size_t p = 0; p < r.solution.names.size(); ++p) {
        if (!r.solution.identified[p] && !r.solution.removed[p]) {
            w.push_back(fmt::format("{} is not identified (set to 0, absorbed by the parameters it is confounded with)", r.solution.names[p]));
        }
    }
    for (const auto& v : r.violations) w.push_back(describe(v));
    return w;
}

namespace {

// "segments: 2 of 3 used (--on-gap split)", then one line per segment not used, with its reason; for several
// logs (--in a --in b) one line per log or segment, used or not, with its equations.
std::string segment_lines(const std::string& what, const std::vector<SegmentReport>& segments) {
    if (segments.empty()) return "";
    const auto used = std::count_if(segments.begin(), segments.end(), [](const SegmentReport& r) { return r.used; });
    const bool several_logs = std::any_of(segments.begin(), segments.end(), [](const SegmentReport& r) { return !r.log.empty(); });
    std::string s = fmt::format("{}: {} of {} used{}\n", what, used, segments.size(), several_logs ? "" : " (--on-gap split)");
    for (const auto& r : segments) {
        const std::string lines = r.first_line == 0 ? std::string() : fmt::format(" lines {}-{}", r.first_line, r.last_line);
        if (several_logs) {
            s += fmt::format("  {}{} ({:.4g} s, {} samples): {}\n", r.log, lines, r.duration, r.samples,
                             r.used ? fmt::format("{} equations per joint", r.rows) : "not used: " + r.why);
        } else if (!r.used) {
            s += fmt::format("  not used:{} ({:.4g} s, {} samples): {}\n", lines, r.duration, r.samples, r.why);
        }
    }
    return s;
}

}  // namespace

std::string format_table(const std::vector<MethodResult>& results, const ReportContext& ctx) {
    const bool truth = !ctx.truth.empty();
    std::string s = fmt::format("Identification of {} ({} model)\n", ctx.log_source, ctx.model_name);
    for (const auto& r : results) {
        s += segment_lines(method_title(r) + " segments", r.segments) + segment_lines(method_title(r) + " validation segments", r.validation_segments);
    }
    std::string head = fmt::format("{:<10}", "P");
    std::string sub = fmt::format("{:<10}", "");
    for (const auto& r : results) {
        head += fmt::format(" | {:^34}", method_title(r) + (r.solution.weighted ? " (weighted)" : ""));
        sub += fmt::format(" | {:>11} {:>11} {:>10}", "X^", "2 sigma", "%sigma_r");
    }
    if (truth) {
        head += fmt::format(" | {:^10}", "truth");
        sub += fmt::format(" | {:>10}", "value");
        for (const auto& r : results) {
            head += fmt::format(" {:>9}", "err %");
            sub += fmt::format(" {:>9}", method_title(r).substr(0, 9));
        }
    }
    s += head + "\n" + sub + "\n" + std::string(sub.size(), '-') + "\n";
    const auto& names = results.front().solution.names;
    for (std::size_t p = 0; p < names.size(); ++p) {
        std::string line = fmt::format("{:<10}", names[p]);
        for (const auto& r : results) {
            const auto& sol = r.solution;
            const auto i = static_cast<Eigen::Index>(p);
            if (!sol.identified[p]) {
                line += fmt::format(" | {:>34}", sol.removed[p] ? "removed (non-essential)" : "NOT IDENTIFIABLE");
            } else {
                line += fmt::format(" | {:>11} {:>11} {:>10}", num(sol.x[i], "{:.5g}"), num(2 * sol.std_dev[i], "{:.3g}"), num(sol.rel_std_percent[i], "{:.3g}"));
            }
        }
        if (truth) {
            const auto it = ctx.truth.find(names[p]);
            const double tv = it == ctx.truth.end() ? NAN : it->second;
            line += fmt::format(" | {:>10}", num(tv, "{:.5g}"));
            for (const auto& r : results) {
                const double x = r.solution.x[static_cast<Eigen::Index>(p)];
                line += fmt::format(" {:>9}", num(tv != 0.0 ? 100.0 * (x - tv) / std::abs(tv) : NAN, "{:+.3f}"));
            }
        }
        s += line + "\n";
    }
    s += std::string(sub.size(), '-') + "\n";
    auto row = [&](const std::string& label, auto value) {
        std::string line = fmt::format("{:<22}", label);
        for (const auto& r : results) line += fmt::format(" | {:>22}", value(r));
        s += line + "\n";
    };
    row("number of equations", [](const MethodResult& r) { return fmt::format("{}", r.solution.equations); });
    row("cond(W)", [](const MethodResult& r) { return num(r.solution.cond, "{:.4g}"); });
    row("relative error norm %", [](const MethodResult& r) { return num(100 * r.solution.relative_error_norm, "{:.4g}"); });
    for (std::size_t j = 0; j < results.front().solution.joint_residual_rms.size(); ++j) {
        row(fmt::format("residual RMS joint {}", j + 1), [j](const MethodResult& r) { return num(r.solution.joint_residual_rms[j], "{:.4g}") + " N.m"; });
    }
    for (const auto& r : results) {
        s += fmt::format("{}: {}; {}\n", method_title(r), settings_line(r.info), describe(r.torque_delay));
        s += fmt::format("{}: {}\n", method_title(r), describe_std(r));
        if (r.estimator) s += fmt::format("{}: {}\n", method_title(r), describe_estimator(*r.estimator));
        if (r.info.bandwidth_estimated) s += fmt::format("{} bandwidth estimate: {}\n", method_title(r), r.info.bandwidth_estimate.description);
        if (r.coulomb_smoothing) s += fmt::format("{} {}\n", method_title(r), describe(*r.coulomb_smoothing, ctx.joint_names));
        if (r.physical) s += fmt::format("{} {}\n", method_title(r), describe(*r.physical));
        if (r.presliding_displacement) s += fmt::format("{} {}\n", method_title(r), describe(*r.presliding_displacement, ctx.joint_names));
        if (r.essential) {
            s += fmt::format("{} essential parameters (drop largest %sigma_r above threshold):\n", method_title(r));
            for (const auto& step : r.essential->steps) {
                if (step.removed.empty()) s += fmt::format("  full model: {} parameters, relative error norm {:.4g} %\n", step.parameters, 100 * step.relative_error_norm);
                else s += fmt::format("  - {} (%sigma_r {:.3g}) -> {} parameters, relative error norm {:.4g} %\n", step.removed, step.removed_rel_std,
                                      step.parameters, 100 * step.relative_error_norm);
            }
        }
        if (r.static_validation) {
            const auto& v = *r.static_validation;
            s += fmt::format("{} static validation on {} ({} samples at rest): measured - model torque", method_title(r), v.source, v.samples);
            for (std::size_t j = 0; j < v.joints.size(); ++j) {
                const auto& e = v.joints[j];
                s += fmt::format(" joint {} {:+.4g} N.m ({:.4g} vs {:.4g}{});", j + 1, e.error, e.measured, e.predicted,
                                 std::isnan(e.coulomb) ? "" : e.within_friction ? fmt::format(", within friction +-{:.3g}", e.coulomb)
                                                                                : fmt::format(", OUTSIDE friction +-{:.3g}", e.coulomb));
            }
            s += fmt::format(" relative error {:.4g} %\n", 100 * v.relative_error);
        }
        if (r.validation) {
            const auto& v = *r.validation;
            s += fmt::format("{} validation on {} ({} decimated samples per joint): filtered RMS error", method_title(r), v.source, v.samples);
            for (std::size_t j = 0; j < v.rms_error.size(); ++j) s += fmt::format(" joint {} {:.4g} N.m;", j + 1, v.rms_error[j]);
            s += fmt::format(" raw full-rate RMS error (differentiators at {:.3g} Hz)", v.raw_differentiator_cutoff);
            for (std::size_t j = 0; j < v.raw_rms_error.size(); ++j) s += fmt::format(" joint {} {:.4g} N.m;", j + 1, v.raw_rms_error[j]);
            s += fmt::format(" relative error {:.4g} %\n", 100 * v.relative_error);
        }
    }
    for (const auto& w : ctx.warnings) s += "warning: " + w + "\n";
    return s;
}

void write_report(const std::string& directory, const std::vector<MethodResult>& results, const ReportContext& ctx) {
    std::error_code ec;
    std::filesystem::create_directories(directory, ec);
    if (ec) throw InputError(fmt::format("--report {}: cannot create directory: {}", directory, ec.message()));
    std::string md = fmt::format("# Identification report: {}\n\nModel: `{}`.\n\n## Table II\n\n```\n{}```\n\n", ctx.log_source, ctx.model_name,
                                 format_table(results, ctx));
    for (const auto& r : results) {
        const std::string m = to_string(r.info.method);
        const auto joints = r.plot.y.size();
        const auto c = static_cast<Eigen::Index>(r.solution.names.size());
        Eigen::VectorXd x = r.solution.x.unaryExpr([](double v) { return std::isnan(v) ? 0.0 : v; });
        std::vector<plot::Panel> panels;
        for (std::size_t j = 0; j < joints; ++j) {
            plot::Series measured{"measured (filtered)", r.plot.t, r.plot.y[j], "lines lw 1.5"};
            plot::Series model{"model W X^", r.plot.t, {}, "lines lw 1 dt 2"};
            for (std::size_t k = 0; k < r.plot.t.size(); ++k) {
                double v = 0.0;
                for (Eigen::Index p = 0; p < c; ++p) v += r.plot.w[j][k * static_cast<std::size_t>(c) + static_cast<std::size_t>(p)] * x[p];
                model.y.push_back(v);
            }
            plot::Series error{"error", r.plot.t, {}, "lines lw 1"};
            for (std::size_t k = 0; k < r.plot.t.size(); ++k) error.y.push_back(r.plot.y[j][k] - model.y[k]);
            panels.push_back({fmt::format("{}: joint {} torque", m, j + 1), "t (s)", "N.m", false, false, {measured, model}, "set key top right"});
            panels.push_back({fmt::format("{}: joint {} error (measured - model)", m, j + 1), "t (s)", "N.m", false, false, {error}, ""});
        }
        const std::string png = fmt::format("torque_{}.png", m);
        plot::render_png((std::filesystem::path(directory) / png).string(), panels);
        md += fmt::format("## {}\n\n{}\n\n![torques]({})\n\n", method_title(r), settings_line(r.info), png);
        if (r.validation) {
            std::vector<plot::Panel> vp;
            for (std::size_t j = 0; j < r.validation->measured.size(); ++j) {
                vp.push_back({fmt::format("validation ({}): joint {}", m, j + 1), "t (s)", "N.m", false, false,
                              {{"measured", r.validation->t, r.validation->measured[j], "lines lw 1"},
                               {"predicted", r.validation->t, r.validation->predicted[j], "lines lw 1 dt 2"}},
                              "set key top right"});
            }
            const std::string vpng = fmt::format("validation_{}.png", m);
            plot::render_png((std::filesystem::path(directory) / vpng).string(), vp);
            md += fmt::format("Validation on `{}`: relative error {:.4g} %.\n\n![validation]({})\n\n", r.validation->source, 100 * r.validation->relative_error, vpng);
        }
    }
    std::ofstream out(std::filesystem::path(directory) / "report.md");
    if (!out) throw InputError(fmt::format("--report {}: cannot write report.md", directory));
    out << md;
}

}  // namespace jacobid::identify
