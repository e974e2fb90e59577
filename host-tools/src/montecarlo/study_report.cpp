// SPDX-License-Identifier: MIT
#include "montecarlo/study_report.hpp"

#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/errors.hpp"
#include "plot/gnuplot.hpp"

namespace jacobid::montecarlo {
namespace {

std::string acceptance_line(const Acceptance& a) {
    return fmt::format("acceptance: |mean error| <= {:g} % or within {:g} standard errors (SE); spread (empirical std / mean reported std) in "
                       "{:g}..{:g}; coverage of the truth by +-2 reported std >= {:g} %",
                       a.max_error_percent, a.standard_errors, a.min_spread, a.max_spread, 100.0 * a.min_coverage);
}

std::string flags(const ParameterSummary& s) {
    std::string f;
    if (!s.error_ok) f += " error";
    if (!s.spread_ok) f += " spread";
    if (!s.coverage_ok) f += " coverage";
    return f.empty() ? "ok" : "<-" + f;
}

std::string number(double v, const char* spec) { return std::isfinite(v) ? fmt::format(spec, v) : std::string("-"); }

std::string method_table(const Study& study, const MethodRuns& runs, const Acceptance& acceptance) {
    std::string t = fmt::format("{:<10} {:>11} {:>11} {:>9} {:>7} {:>5} {:>10} {:>10} {:>6} {:>6}  {}\n", "param", "truth", "mean", "error %",
                                "SE %", "<=3SE", "emp std", "rep std", "spread", "cover", "flags");
    for (const auto& s : summarize(study, runs, acceptance)) {
        t += fmt::format("{:<10} {:>11.5g} {:>11} {:>9} {:>7} {:>5} {:>10} {:>10} {:>6} {:>6}  {}\n", s.name, s.truth, number(s.mean, "{:.5g}"),
                         number(s.mean_error_percent, "{:+.4f}"), number(s.standard_error_percent, "{:.4f}"), s.within_3se ? "yes" : "no",
                         number(s.empirical_std, "{:.3g}"), number(s.mean_reported_std, "{:.3g}"), number(s.spread_ratio, "{:.2f}"),
                         number(100.0 * s.coverage_2std, "{:.0f} %"), flags(s));
    }
    return t;
}

// Per run, (x - truth) / reported std at the parameter's index (runs spread sideways), and per parameter the
// mean error in standard errors: the +-2 and +-3 bands show at a glance what the table says.
std::vector<plot::Panel> method_panels(const Study& study, const MethodRuns& runs, const Acceptance& acceptance) {
    const auto summaries = summarize(study, runs, acceptance);
    const double count = static_cast<double>(study.names.size());
    std::string xtics = "set xtics (";
    for (std::size_t p = 0; p < study.names.size(); ++p) xtics += fmt::format("{}\"{}\" {}", p ? ", " : "", study.names[p], p + 1);
    xtics += fmt::format(")\nset xrange [0.4:{}]\nset key outside right top\n", count + 0.6);
    plot::Series z{"runs", {}, {}, "points pt 7 ps 0.5"}, t{"mean error / SE", {}, {}, "points pt 7 ps 1.2"};
    for (std::size_t p = 0; p < study.names.size(); ++p) {
        const auto i = static_cast<Eigen::Index>(p);
        for (std::size_t k = 0; k < runs.x.size(); ++k) {
            const double v = (runs.x[k][i] - study.truth[i]) / runs.std_dev[k][i];
            if (!std::isfinite(v)) continue;
            z.x.push_back(static_cast<double>(p + 1) - 0.3 + 0.6 * static_cast<double>(k) / static_cast<double>(runs.x.size()));
            z.y.push_back(v);
        }
        const double se = summaries[p].empirical_std / std::sqrt(static_cast<double>(summaries[p].runs));
        const double tv = (summaries[p].mean - summaries[p].truth) / se;
        if (std::isfinite(tv)) {
            t.x.push_back(static_cast<double>(p + 1));
            t.y.push_back(tv);
        }
    }
    auto band = [&](double level, const char* title) {
        return plot::Series{title, {0.4, count + 0.6}, {level, level}, "lines lw 2 dt 2 lc rgb 'red'"};
    };
    const char* method = identify::to_string(runs.method);
    return {{fmt::format("{}: normalized error (x - truth) / reported std, {} runs", method, runs.x.size()), "", "(x - truth) / sigma", false,
             false, {z, band(2.0, "+-2"), band(-2.0, "")}, xtics},
            {fmt::format("{}: mean error in standard errors of the mean", method), "", "(mean - truth) / SE", false, false,
             {t, band(acceptance.standard_errors, "+-3 SE"), band(-acceptance.standard_errors, "")}, xtics}};
}

nlohmann::json to_json(const std::vector<ParameterSummary>& summaries, const MethodRuns& runs) {
    nlohmann::json params = nlohmann::json::object();
    bool all_ok = true;
    for (std::size_t p = 0; p < summaries.size(); ++p) {
        const auto& s = summaries[p];
        all_ok = all_ok && s.ok();
        std::vector<double> estimates, reported;
        for (std::size_t k = 0; k < runs.x.size(); ++k) {
            estimates.push_back(runs.x[k][static_cast<Eigen::Index>(p)]);
            reported.push_back(runs.std_dev[k][static_cast<Eigen::Index>(p)]);
        }
        // nlohmann writes NaN as null: a statistic that does not exist, or a run that did not identify the parameter.
        params[s.name] = {{"truth", s.truth},
                          {"runs", s.runs},
                          {"mean", s.mean},
                          {"mean_error_percent", s.mean_error_percent},
                          {"standard_error_percent", s.standard_error_percent},
                          {"within_3se", s.within_3se},
                          {"empirical_std", s.empirical_std},
                          {"mean_reported_std", s.mean_reported_std},
                          {"spread_ratio", s.spread_ratio},
                          {"coverage_2std", s.coverage_2std},
                          {"error_ok", s.error_ok},
                          {"spread_ok", s.spread_ok},
                          {"coverage_ok", s.coverage_ok},
                          {"estimates", estimates},
                          {"reported_std", reported}};
    }
    return {{"all_ok", all_ok}, {"parameters", params}};
}

}  // namespace

std::string format_table(const Study& study, const StudyContext& context) {
    std::string t = fmt::format("jacobid montecarlo: {} ({}), {}; {:.1f} s on {} thread{}\n{}\n", study.model_name, context.robot, context.settings_line,
                                study.seconds, study.threads, study.threads == 1 ? "" : "s", acceptance_line(context.acceptance));
    for (const auto& runs : study.methods) t += fmt::format("\n[{}]\n{}", identify::to_string(runs.method), method_table(study, runs, context.acceptance));
    return t;
}

nlohmann::json to_json(const Study& study, const StudyContext& context) {
    const Acceptance& a = context.acceptance;
    nlohmann::json j;
    j["model"] = study.model_name;
    j["robot"] = context.robot;
    j["settings"] = context.settings;
    j["settings"]["seeds"] = study.seeds;
    j["settings"]["noise_seeds"] = study.noise_seeds;
    j["acceptance"] = {{"max_error_percent", a.max_error_percent}, {"standard_errors", a.standard_errors}, {"min_coverage", a.min_coverage},
                       {"min_spread", a.min_spread},               {"max_spread", a.max_spread}};
    j["parameter_order"] = study.names;
    j["wall_seconds"] = study.seconds;
    j["threads"] = study.threads;
    for (const auto& runs : study.methods) j["methods"][identify::to_string(runs.method)] = to_json(summarize(study, runs, a), runs);
    return j;
}

void write_report(const std::string& directory, const Study& study, const StudyContext& context) {
    std::error_code ec;
    std::filesystem::create_directories(directory, ec);
    if (ec) throw InputError(fmt::format("--report {}: cannot create the directory: {}", directory, ec.message()));
    std::string md = fmt::format("# Monte Carlo study: {}\n\n{} ({}), {}; {:.1f} s on {} threads.\n\n{}.\n\n", study.model_name, study.model_name,
                                 context.robot, context.settings_line, study.seconds, study.threads, acceptance_line(context.acceptance));
    for (const auto& runs : study.methods) {
        const std::string m = identify::to_string(runs.method);
        const std::string png = fmt::format("montecarlo_{}.png", m);
        plot::render_png((std::filesystem::path(directory) / png).string(), method_panels(study, runs, context.acceptance));
        md += fmt::format("## {}\n\n```\n{}```\n\n![normalized errors]({})\n\n", m, method_table(study, runs, context.acceptance), png);
    }
    std::ofstream out(std::filesystem::path(directory) / "report.md");
    if (!out) throw InputError(fmt::format("--report {}: cannot write report.md", directory));
    out << md;
}

}  // namespace jacobid::montecarlo
