// SPDX-License-Identifier: MIT
#include "diagnose/diagnosis_report.hpp"

#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <tuple>

#include "core/errors.hpp"
#include "plot/gnuplot.hpp"

namespace jacobid::diagnose {
namespace {

std::string effect_label(const EffectEstimate& e) { return e.test.label(); }

// A figure of the gap table; a NaN (no segment left to measure: all diverged) is said, never printed as a number.
std::string figure(double v) { return std::isfinite(v) ? fmt::format("{:.4g}", v) : "n/a"; }
// A standard deviation; an infinite one (a delay at the edge of its search, where RSS(delay) has no
// curvature) is "n/a", never "inf".
std::string spread(double v) { return std::isfinite(v) ? fmt::format("{:.2g}", v) : "n/a"; }

nlohmann::json snapshot_json(const ModelSnapshot& m, const std::vector<std::string>& joint_names) {
    nlohmann::json j;
    j["residual_rms"] = m.residual_rms;
    j["heldout_rms"] = m.heldout_rms;
    j["heldout_weighted_rms"] = m.heldout_weighted;
    j["horizon_rms"] = m.horizon.rms_error;
    j["horizon_end_rms"] = m.horizon.end_error;
    j["horizon_segments"] = m.horizon.segments;
    j["horizon_diverged"] = m.horizon.diverged;
    nlohmann::json diverged = nlohmann::json::array();
    for (const auto& d : m.horizon.divergences) {
        diverged.push_back({{"t", d.t}, {"after", d.after}, {"joint", d.joint >= 0 ? nlohmann::json(d.joint + 1) : nlohmann::json(nullptr)}, {"why", d.why}});
    }
    j["horizon_divergences"] = diverged;
    j["relative_error_norm"] = m.solution.relative_error_norm;
    nlohmann::json params = nlohmann::json::object();
    for (std::size_t p = 0; p < m.solution.names.size(); ++p) {
        const double x = m.solution.x[static_cast<Eigen::Index>(p)];
        params[m.solution.names[p]] = std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x);
    }
    j["parameters"] = params;
    nlohmann::json joints = nlohmann::json::array();
    for (std::size_t k = 0; k < m.analysis.size(); ++k) {
        const auto& a = m.analysis[k];
        nlohmann::json bins = nlohmann::json::array();
        for (const auto& b : a.velocity) bins.push_back({{"bin", b.label}, {"count", b.count}, {"mean", b.mean}, {"rms", b.rms}});
        nlohmann::json motion = nlohmann::json::array();
        for (const auto& st : a.motion) {
            motion.push_back({{"state", st.state},     {"count", st.count},           {"mean", st.mean},
                              {"rms", st.rms},         {"row_share", st.row_share}, {"energy_share", st.energy_share}});
        }
        joints.push_back({{"joint", k + 1},
                          {"name", k < joint_names.size() ? joint_names[k] : ""},
                          {"rms", a.rms},
                          {"velocity_bins", bins},
                          {"motion_states", motion},
                          {"angle_dominant_order", a.dominant_order},
                          {"angle_dominant_amplitude", a.dominant_amplitude},
                          {"rho1", a.autocorrelation.empty() ? 0.0 : a.autocorrelation.front()},
                          {"n_eff", a.n_eff},
                          {"findings", a.findings}});
    }
    j["joints"] = joints;
    return j;
}

nlohmann::json test_json(const CandidateTest& t) {
    return {{"candidate", t.label()}, {"value", t.value},          {"std", t.std},        {"chi2", t.chi2},
            {"dof", t.dof},          {"p_value", t.p_value},      {"adjusted_p", t.adjusted_p},
            {"heldout_before", t.heldout_before}, {"heldout_after", t.heldout_after}, {"heldout_gain", t.gain},
            {"significant", t.significant}, {"generalizes", t.generalizes}};
}

}  // namespace

nlohmann::json to_json(const Diagnosis& d) {
    nlohmann::json j;
    j["effects"] = nlohmann::json::array();
    for (const auto& e : d.effects) {
        nlohmann::json x = {{"name", sim::effect_name(e.term.kind)},
                            {"joint", e.term.joint >= 0 ? nlohmann::json(e.term.joint + 1) : nlohmann::json(nullptr)},
                            {"value", e.value},
                            {"std", e.std},
                            {"unit", sim::effect_unit(e.term.kind)},
                            {"label", effect_label(e)},
                            {"coefficients", std::vector<double>(e.coefficients.data(), e.coefficients.data() + e.coefficients.size())},
                            {"selection", test_json(e.test)}};
        if (e.term.kind == sim::EffectKind::Stribeck) x["velocity"] = e.term.velocity;
        if (e.term.kind == sim::EffectKind::Presliding) x["displacement"] = e.term.displacement;
        if (e.term.kind == sim::EffectKind::CoulombSmoothing) x["alpha"] = e.term.alpha;
        if (e.term.kind == sim::EffectKind::Cogging) x["order"] = e.term.order;
        j["effects"].push_back(x);
    }
    j["before"] = snapshot_json(d.before, d.joint_names);
    j["after"] = snapshot_json(d.after, d.joint_names);
    j["verdict"] = d.verdict;
    j["log"] = d.log_source;
    j["logs"] = d.log_sources;  // one per --in (the field "log" joins them)
    j["validation"] = d.validation_source.empty() ? nlohmann::json(nullptr) : nlohmann::json(d.validation_source);
    j["model"] = d.model_name;
    j["torque_delay"] = d.delay;
    nlohmann::json steps = nlohmann::json::array();
    for (const auto& s : d.selection.steps) {
        nlohmann::json top = nlohmann::json::array();
        for (const auto& t : s.top) top.push_back(test_json(t));
        steps.push_back({{"rows", s.rows}, {"n_eff", s.n_eff}, {"heldout", s.heldout}, {"tested", s.tested}, {"accepted", s.accepted}, {"top", top}});
    }
    j["selection"] = {{"heldout", d.selection.heldout_kind}, {"joint_sigma", d.selection.joint_sigma}, {"steps", steps},
                      {"collinear_candidates", d.selection.skipped}};
    j["notes"] = d.notes;
    j["decimation"] = d.info.decimation;
    j["rows"] = d.t.size();
    j["catalogue_columns"] = d.catalogue_columns;
    j["seconds"] = d.seconds;
    return j;
}

std::string format_text(const Diagnosis& d) {
    std::string s = fmt::format("jacobid diagnose: {} ({}), {} rows per joint after decimation {}\n", d.log_source, d.model_name, d.t.size(),
                                d.info.decimation);
    s += fmt::format("Held-out data: {}\n\n", d.selection.heldout_kind);
    s += "Where the nominal model disagrees with the data:\n";
    for (std::size_t j = 0; j < d.before.analysis.size(); ++j) {
        s += fmt::format("  joint {} (residual RMS {:.4g} N.m)\n", j + 1, d.before.analysis[j].rms);
        for (const auto& f : d.before.analysis[j].findings) s += "    - " + f + "\n";
    }
    s += "\nSelection (forward stepwise; chi2 with n_eff, Bonferroni; held-out gain):\n";
    for (std::size_t k = 0; k < d.selection.steps.size(); ++k) {
        const auto& st = d.selection.steps[k];
        s += fmt::format("  step {}: {} candidates, n_eff {:.0f} of {:.0f} rows\n", k + 1, st.tested, st.n_eff, st.rows);
        for (const auto& t : st.top) {
            s += fmt::format("    {:<38} value {:>10.4g} +- {:<9} chi2 {:>9.1f}  adj. p {:>8.2g}  held-out {:+6.1f} %  {}\n", t.label(), t.value,
                             spread(t.std), t.chi2, t.adjusted_p, -100.0 * t.gain,
                             t.accepted() ? "pass" : (t.significant ? "fails held-out" : "not significant"));
        }
    }
    s += "\nNamed effects:\n";
    if (d.effects.empty()) s += "  none\n";
    for (const auto& e : d.effects) {
        s += fmt::format("  {:<38} {:>10.4g} +- {} {}\n", effect_label(e), e.value, spread(e.std), sim::effect_unit(e.term.kind));
        if (e.term.kind == sim::EffectKind::CoulombSmoothing) {
            s += fmt::format("    in identify and simulate: friction: alpha {:g} for joint {} (a list, one alpha per joint, or alpha: auto)\n",
                             e.term.alpha, e.term.joint + 1);
        }
    }
    // The model option that carries named presliding into identify, simulate and the exported model: one for
    // the whole robot (FDj on every joint), with the displacements the diagnosis chose.
    std::string presliding;
    for (const auto& e : d.effects) {
        if (e.term.kind == sim::EffectKind::Presliding) presliding += fmt::format("{}joint {} {:g} rad", presliding.empty() ? "" : ", ", e.term.joint + 1, e.term.displacement);
    }
    if (!presliding.empty()) {
        s += fmt::format("  presliding in identify and simulate: friction: {{presliding: dahl}} (FDj on every joint; presliding_displacement: auto "
                         "chooses x_p per joint, a list fixes it; chosen here: {})\n",
                         presliding);
    }
    s += "\nGap before -> after, per joint:\n";
    const std::size_t joints = d.before.residual_rms.size();
    s += fmt::format("  {:<34}", "");
    for (std::size_t j = 0; j < joints; ++j) s += fmt::format(" {:>21}", fmt::format("joint {}", j + 1));
    s += "\n";
    auto row = [&](const char* name, const std::vector<double>& a, const std::vector<double>& b, double scale, const char* unit) {
        s += fmt::format("  {:<34}", fmt::format("{} ({})", name, unit));
        for (std::size_t j = 0; j < joints && j < a.size() && j < b.size(); ++j) {
            s += fmt::format(" {:>21}", fmt::format("{} -> {}", figure(scale * a[j]), figure(scale * b[j])));
        }
        s += "\n";
    };
    row("torque residual RMS", d.before.residual_rms, d.after.residual_rms, 1.0, "N.m");
    row("held-out torque RMS", d.before.heldout_rms, d.after.heldout_rms, 1.0, "N.m");
    row("short-horizon simulation RMS", d.before.horizon.rms_error, d.after.horizon.rms_error, 1e3, "mrad");
    for (const auto& [when, h] : {std::pair{"before", &d.before.horizon}, std::pair{"after", &d.after.horizon}}) {
        if (h->diverged) s += fmt::format("note: short-horizon simulation {}: {}\n", when, h->divergence_summary());
    }
    for (const auto& n : d.notes) s += "note: " + n + "\n";
    s += "\n" + d.verdict + "\n";
    return s;
}

void write_report(const std::string& directory, const Diagnosis& d) {
    std::error_code ec;
    std::filesystem::create_directories(directory, ec);
    if (ec) throw InputError(fmt::format("--report {}: cannot create directory: {}", directory, ec.message()));
    const std::size_t joints = d.state.size();
    for (const auto& [column, name, unit] : {std::tuple{1, "velocity", "qd (rad/s)"}, std::tuple{0, "position", "q (rad)"}}) {
        std::vector<plot::Panel> panels;
        for (std::size_t j = 0; j < joints; ++j) {
            const Eigen::VectorXd x = d.state[j].col(column);
            const std::vector<double> xs(x.data(), x.data() + x.size());
            const auto& rb = d.before.residual[j];
            const auto& ra = d.after.residual[j];
            panels.push_back({fmt::format("joint {}: torque residual vs {}", j + 1, name), unit, "N.m", false, false,
                              {{"before (nominal model)", xs, std::vector<double>(rb.data(), rb.data() + rb.size()), "points pt 7 ps 0.3"},
                               {"after (with the named effects)", xs, std::vector<double>(ra.data(), ra.data() + ra.size()), "points pt 7 ps 0.3"}},
                              "set key top right"});
        }
        plot::render_png((std::filesystem::path(directory) / fmt::format("residual_{}.png", name)).string(), panels);
    }
    // Spectrum against the angle and residual autocorrelation, before and after.
    std::vector<plot::Panel> spectra;
    for (std::size_t j = 0; j < joints; ++j) {
        const auto& b = d.before.analysis[j];
        const auto& a = d.after.analysis[j];
        spectra.push_back({fmt::format("joint {}: residual amplitude vs harmonic order of the joint angle", j + 1), "order (periods per rev)", "N.m",
                           false, false,
                           {{"before", b.angle_orders, b.angle_amplitude, "linespoints pt 7 ps 0.5"},
                            {"after", a.angle_orders, a.angle_amplitude, "linespoints pt 7 ps 0.5"}},
                           "set key top right"});
        std::vector<double> lags;
        for (std::size_t k = 1; k <= b.autocorrelation.size(); ++k) lags.push_back(static_cast<double>(k));
        spectra.push_back({fmt::format("joint {}: residual autocorrelation (decimated rows)", j + 1), "lag (rows)", "rho", false, false,
                           {{"before", lags, b.autocorrelation, "linespoints pt 7 ps 0.5"},
                            {"after", lags, a.autocorrelation, "linespoints pt 7 ps 0.5"}},
                           "set key top right; set yrange [-1:1]"});
    }
    plot::render_png((std::filesystem::path(directory) / "residual_spectrum.png").string(), spectra, 1100, 300);
    std::string md = fmt::format("# Model-discrepancy diagnosis: {}\n\nModel `{}`; held-out data: {}.\n\n**{}**\n\n", d.log_source, d.model_name,
                                 d.selection.heldout_kind, d.verdict);
    md += "## Named effects\n\n| effect | value | std | unit | chi2 (n_eff) | adjusted p | held-out gain |\n|---|---|---|---|---|---|---|\n";
    for (const auto& e : d.effects) {
        md += fmt::format("| {} | {:.4g} | {} | {} | {:.1f} | {:.2g} | {:.1f} % |\n", effect_label(e), e.value, spread(e.std), sim::effect_unit(e.term.kind),
                          e.test.chi2, e.test.adjusted_p, 100.0 * e.test.gain);
    }
    if (d.effects.empty()) md += "| none | | | | | | |\n";
    md += "\n## Gap before and after\n\n| joint | residual RMS (N.m) | held-out RMS (N.m) | short-horizon simulation RMS (mrad) |\n|---|---|---|---|\n";
    for (std::size_t j = 0; j < d.before.residual_rms.size(); ++j) {
        md += fmt::format("| {} | {} -> {} | {} -> {} | {} -> {} |\n", j + 1, figure(d.before.residual_rms[j]), figure(d.after.residual_rms[j]),
                          figure(d.before.heldout_rms[j]), figure(d.after.heldout_rms[j]), figure(1e3 * d.before.horizon.rms_error[j]),
                          figure(1e3 * d.after.horizon.rms_error[j]));
    }
    for (const auto& [when, h] : {std::pair{"before", &d.before.horizon}, std::pair{"after", &d.after.horizon}}) {
        if (h->diverged) md += fmt::format("\nShort-horizon simulation {}: {}.\n", when, h->divergence_summary());
    }
    md += "\n## Where the nominal model disagrees\n\n";
    for (std::size_t j = 0; j < d.before.analysis.size(); ++j) {
        md += fmt::format("Joint {}:\n\n", j + 1);
        for (const auto& f : d.before.analysis[j].findings) md += "- " + f + "\n";
        md += "\n";
    }
    md += "## Residual against velocity and position\n\n![residual vs velocity](residual_velocity.png)\n\n![residual vs position](residual_position.png)\n\n"
          "## Periodic content against the joint angle, whiteness\n\n![spectrum and autocorrelation](residual_spectrum.png)\n\n";
    md += "## Selection steps\n\n```\n" + format_text(d) + "```\n";
    std::ofstream out(std::filesystem::path(directory) / "report.md");
    if (!out) throw InputError(fmt::format("--report {}: cannot write report.md", directory));
    out << md;
}

}  // namespace jacobid::diagnose
