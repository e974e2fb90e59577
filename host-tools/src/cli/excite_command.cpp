// SPDX-License-Identifier: MIT
// jacobid excite: an optimized excitation trajectory for identification (docs/excite.md): finite Fourier
// series per joint, at rest at a pose at both ends of every period, an information criterion of the base
// parameters (d-optimal by default, weighed by the torque noise and the prior) optimized within the joints'
// limits; each base parameter's predicted std, beside that of a --compare trajectory or log; CSV at the
// control rate, JSON, optional PNG.
#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <nlohmann/json.hpp>

#include "cli/command.hpp"
#include "cli/excite_prediction.hpp"
#include "options/excite_options.hpp"
#include "options/log_format_options.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"
#include "options/robot_files.hpp"
#include "core/errors.hpp"
#include "core/per_joint.hpp"
#include "excite/design_checks.hpp"
#include "excite/excitation_design.hpp"
#include "excite/frequency_rule.hpp"
#include "excite/identification_bandwidth.hpp"
#include "excite/motion_information.hpp"
#include "excite/payload_target.hpp"
#include "excite/reference_motion.hpp"
#include "plot/gnuplot.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::cli {
namespace {

struct Sampled {
    std::vector<double> t;
    std::vector<std::vector<double>> q, qd, qdd, tau;  // per joint
    std::vector<std::vector<double>> point;            // x, y, z of the workspace point (empty: no workspace)
};

Sampled sample(const excite::FourierTrajectory& trajectory, const robot::RobotModel& model, const Eigen::VectorXd& x, double duration, double rate,
               const std::optional<excite::Workspace>& workspace) {
    const int n = trajectory.joints();
    Sampled s;
    s.q.resize(static_cast<std::size_t>(n)), s.qd.resize(static_cast<std::size_t>(n)), s.qdd.resize(static_cast<std::size_t>(n)),
        s.tau.resize(static_cast<std::size_t>(n));
    const auto count = static_cast<std::size_t>(std::llround(duration * rate));
    Eigen::VectorXd q(n), qd(n), qdd(n);
    Eigen::MatrixXd Y(n, model.parameter_count());
    if (workspace) s.point.resize(3);
    for (std::size_t i = 0; i <= count; ++i) {
        const double t = static_cast<double>(i) / rate;
        trajectory.evaluate(t, q, qd, qdd);
        if (workspace) {
            const Eigen::Vector3d p = workspace->frame.point(q, nullptr);
            for (std::size_t a = 0; a < 3; ++a) s.point[a].push_back(p[static_cast<Eigen::Index>(a)]);
        }
        model.regressor(q.data(), qd.data(), qdd.data(), Y);
        const Eigen::VectorXd tau = Y * x;
        s.t.push_back(t);
        for (int j = 0; j < n; ++j) {
            const auto k = static_cast<std::size_t>(j);
            s.q[k].push_back(q[j]), s.qd[k].push_back(qd[j]), s.qdd[k].push_back(qdd[j]), s.tau[k].push_back(tau[j]);
        }
    }
    return s;
}

std::string csv(const Sampled& s) {
    const std::size_t n = s.q.size();
    std::string out = "t";
    for (const char* kind : {"q", "qd", "qdd"}) {
        for (std::size_t j = 0; j < n; ++j) out += fmt::format(",{}{}", kind, j + 1);
    }
    out += "\n";
    for (std::size_t i = 0; i < s.t.size(); ++i) {
        out += fmt::format("{:.6f}", s.t[i]);
        for (const auto* v : {&s.q, &s.qd, &s.qdd}) {
            for (std::size_t j = 0; j < n; ++j) out += fmt::format(",{:.17g}", (*v)[j][i]);
        }
        out += "\n";
    }
    return out;
}

void plot(const std::string& path, const Sampled& s, const std::optional<excite::Workspace>& workspace, const std::vector<std::string>& names,
          const excite::Prediction& predicted, const excite::Prediction* compared, bool payload) {
    std::vector<plot::Panel> panels;
    const char* titles[3] = {"position (rad)", "velocity (rad/s)", "motor torque of the model (N.m)"};
    const std::vector<std::vector<double>>* values[3] = {&s.q, &s.qd, &s.tau};
    for (int p = 0; p < 3; ++p) {
        plot::Panel panel{titles[p], "t (s)", titles[p], false, false, {}, ""};
        for (std::size_t j = 0; j < s.q.size(); ++j) panel.series.push_back({fmt::format("joint {}", j + 1), s.t, (*values[p])[j], "lines"});
        panels.push_back(std::move(panel));
    }
    if (workspace) {
        // The point's coordinates with the box's faces as dashed lines of the same colour.
        plot::Panel panel{fmt::format("workspace point of frame {} (base frame, m) and the box", workspace->frame_name), "t (s)", "m", false, false, {}, ""};
        const std::vector<double> ends = {s.t.front(), s.t.back()};
        for (int a = 0; a < 3; ++a) {
            const char axis = "xyz"[a];
            const auto k = static_cast<std::size_t>(a);
            panel.series.push_back({std::string(1, axis), s.t, s.point[k], fmt::format("lines lc {}", a + 1)});
            for (const double bound : {workspace->box.lower[a], workspace->box.upper[a]}) {
                panel.series.push_back({fmt::format("{} = {:g}", axis, bound), ends, {bound, bound}, fmt::format("lines lc {} dt 2", a + 1)});
            }
        }
        panels.push_back(std::move(panel));
    }
    // The predicted relative std of every base parameter, the design's beside --compare's (log scale).
    plot::Panel prediction{payload ? "predicted relative std of each payload parameter (jacobid payload, the arm held known; std / prior scale)"
                                   : "predicted relative std of each base parameter (WLS, std / prior scale)",
                           payload ? "payload parameter (about the last link's frame)" : "base parameter", "relative std (%)", false, true, {}, ""};
    auto series = [&](const excite::Prediction& p, const char* title, const char* style) {
        plot::Series line{title, {}, {}, style};
        for (Eigen::Index k = 0; k < p.relative_std.size(); ++k) {
            if (!std::isfinite(p.relative_std[k])) continue;
            line.x.push_back(static_cast<double>(k + 1));
            line.y.push_back(100.0 * p.relative_std[k]);
        }
        prediction.series.push_back(std::move(line));
    };
    series(predicted, "this design", "linespoints pt 7 ps 0.8 lw 1.5");
    if (compared) series(*compared, "--compare", "linespoints pt 5 ps 0.8 lw 1.5 dt 2");
    std::string tics = "set xtics rotate by 90 right font ',8' (";
    for (std::size_t k = 0; k < names.size(); ++k) tics += fmt::format("{}\"{}\" {}", k ? ", " : "", names[k], k + 1);
    prediction.extra = tics + ")\nset xrange [0:" + std::to_string(names.size() + 1) + "]";
    panels.push_back(std::move(prediction));
    plot::render_png(path, panels);
}

// The trajectory at every control sample as a motion (excite/motion_information.hpp).
excite::SampledMotion motion_of(const Sampled& s) { return {s.q, s.qd, s.qdd, 0, 0}; }

// --criterion i-optimal's default reference: random moves within the design's limits, sampled at 100 Hz.
constexpr double kReferenceSeconds = 60.0, kReferenceRate = 100.0;
constexpr std::uint64_t kReferenceSeed = 1;
std::string reference_name(const ExciteOptions& o) {
    return o.reference.empty() ? fmt::format("{:g} s of random moves within the limits", kReferenceSeconds) : o.reference;
}

// --criterion i-optimal's M: the information per sample of --reference's motion, or of the default reference's
// (docs/excite.md, "Designing for the motion the model will serve").
Eigen::MatrixXd reference_information(const robot::RobotDescription& robot, const robot::RobotModel& model, const std::vector<excite::JointLimits>& limits,
                                      const Eigen::VectorXd& pose, const ExcitePrior& prior, const ExciteOptions& o) {
    if (o.payload) throw InputError("--criterion i-optimal: not with --payload (the payload's designs weigh the payload's parameters only)");
    if (!o.reference.empty()) return excite::reference_information(model, read_compare_motion(o.reference, robot, model, o.compare_format, o.quiet).motion, prior.noise_std);
    for (std::size_t j = 0; j < limits.size(); ++j) {
        if (!std::isfinite(limits[j].lower) || !std::isfinite(limits[j].upper)) {
            throw InputError(fmt::format("--criterion i-optimal: joint {} has no finite position range for the default reference's random moves; give "
                                         "--position-limit or --reference", j + 1));
        }
    }
    return excite::reference_information(model, excite::random_moves(limits, pose, kReferenceSeconds, kReferenceRate, kReferenceSeed), prior.noise_std);
}

// What a design and its predictions are, for the JSON and the text.
struct Outcome {
    const ExciteOptions& o;
    const robot::RobotModel& model;
    const ExcitePrior& prior;   // the noise (and the base parameters' prior)
    const ExcitePrior& target;  // the parameters designed for: the base parameters', or the payload's (--payload)
    const std::vector<std::string>& names;  // of the target
    const std::optional<excite::PayloadTarget>& payload;
    const std::vector<excite::JointLimits>& limits;
    const Eigen::VectorXd& pose;
    const std::optional<excite::Workspace>& box;
    const excite::ExcitationProblem& problem;
    const excite::Design& d;
    const excite::FourierTrajectory& trajectory;
    excite::Prediction predicted;
    Eigen::VectorXd inertial_std;  // --payload: the predicted std of mass, centre of mass, inertia about it
    std::optional<CompareMotion> compared;
    std::optional<excite::Prediction> compared_prediction;
    Eigen::VectorXd compared_inertial_std;
    excite::IdentificationBandwidth bandwidth;
    excite::Prediction after_fp;  // the design's prediction from what identify's decimated rows keep (its F_p)
    bool needs_cutoff = false, worse = false;
    double margin = std::numeric_limits<double>::infinity();  // the workspace point's smallest distance to a face (m)
    int closest = 0;                                          // and that face
    std::string worst_name(const excite::Prediction& p) const { return p.worst >= 0 ? names[static_cast<std::size_t>(p.worst)] : "not identifiable"; }
};

nlohmann::json joints_json(const Outcome& r) {
    nlohmann::json joints = nlohmann::json::array();
    const excite::LimitCheck& c = r.d.check;
    for (int k = 0; k < r.model.joint_count(); ++k) {
        std::vector<double> a, b;
        for (int l = 0; l < r.o.harmonics; ++l) {
            a.push_back(r.trajectory.coefficients(k, 2 * l));
            b.push_back(r.trajectory.coefficients(k, 2 * l + 1));
        }
        joints.push_back({{"a", a},
                          {"b", b},
                          {"max_position", c.peak(k, 0)},
                          {"min_position", c.peak(k, 1)},
                          {"peak_velocity", c.peak(k, 2)},
                          {"peak_acceleration", c.peak(k, 3)},
                          {"peak_torque", c.peak(k, 4)},
                          {"limit_use", {{"upper_position", c.ratio(k, 0)},
                                         {"lower_position", c.ratio(k, 1)},
                                         {"velocity", c.ratio(k, 2)},
                                         {"acceleration", c.ratio(k, 3)},
                                         {"torque", c.ratio(k, 4)}}}});
    }
    return joints;
}

nlohmann::json outcome_json(const Outcome& r) {
    const ExciteOptions& o = r.o;
    const excite::Design& d = r.d;
    const excite::Criterion criterion = *excite::criterion_from_string(o.criterion);
    const int n = r.model.joint_count();
    nlohmann::json j;
    j["criterion"] = o.criterion;
    j["criterion_value"] = d.criterion;
    j["cond"] = d.cond;
    j["duration"] = o.duration;
    j["period"] = 1.0 / o.base_frequency;
    j["base_frequency"] = o.base_frequency;
    j["base_frequency_auto"] = o.base_frequency_text == "auto";
    j["harmonics"] = o.harmonics;
    j["harmonics_auto"] = o.harmonics_text == "auto";
    j["top_frequency"] = excite::top_frequency(r.limits);
    j["rate"] = o.rate;
    j["samples"] = r.problem.samples();
    j["decimation_cutoff_hz"] = o.decimation_cutoff > 0.0 ? nlohmann::json(o.decimation_cutoff) : nlohmann::json();
    j["pose"] = std::vector<double>(r.pose.data(), r.pose.data() + n);
    j["parameters"] = r.model.parameter_names();
    j["noise_std"] = std::vector<double>(r.prior.noise_std.data(), r.prior.noise_std.data() + n);
    j["noise_source"] = r.prior.noise_source;
    j["noise_known"] = r.prior.noise_known;
    j["prior"] = r.prior.values_source;
    j["target"] = r.payload ? "payload" : "base parameters";
    j["predicted"] = prediction_json(r.names, r.target, r.predicted);
    j["predicted"]["score"] = prediction_score(criterion, r.predicted);
    // Added beside the prediction of every sample's information: what identify's rows keep after its F_p.
    nlohmann::json after = prediction_json(r.names, r.target, r.after_fp);
    for (auto& [name, p] : after["parameters"].items()) {
        j["predicted"]["parameters"][name]["std_after_fp"] = p["std"];
        j["predicted"]["parameters"][name]["relative_std_after_fp"] = p["relative_std"];
    }
    after.erase("parameters");
    after["decimation_cutoff_hz"] = r.bandwidth.decimation_cutoff_hz();
    j["predicted"]["after_fp"] = after;
    if (r.compared) {
        j["compare"] = {{"file", o.compare}, {"how", r.compared->how}, {"duration", r.compared->duration}};
        j["compare"]["predicted"] = prediction_json(r.names, r.target, *r.compared_prediction);
        j["compare"]["predicted"]["score"] = prediction_score(criterion, *r.compared_prediction);
        j["compare"]["worst_relative_std_ratio"] = r.predicted.worst_relative_std / r.compared_prediction->worst_relative_std;
        j["compare"]["design_worse"] = r.worse;
    }
    if (r.payload) j["payload"] = payload_json(*r.payload, r.inertial_std, r.compared ? &r.compared_inertial_std : nullptr);
    const excite::IdentificationBandwidth& b = r.bandwidth;
    j["identification"] = {{"velocity_bandwidth_hz", b.velocity_hz},
                           {"torque_bandwidth_hz", b.torque_hz},
                           {"automatic_bandwidth_hz", b.automatic_hz},
                           {"differentiator_bandwidth_hz", b.differentiator_hz},
                           {"default_cutoff_hz", b.default_cutoff_hz()},
                           {"recommended_cutoff_hz", b.recommended_cutoff_hz()},
                           {"identify_options", r.needs_cutoff ? fmt::format("--cutoff {:.3g}", b.recommended_cutoff_hz()) : std::string()}};
    j["evaluations"] = d.evaluations;
    j["starts"] = d.start_criteria;
    j["tightening_rounds"] = d.rounds;
    j["seconds"] = d.seconds;
    j["joints"] = joints_json(r);
    if (r.box) {
        auto vec = [](const Eigen::Vector3d& v) { return std::vector<double>{v.x(), v.y(), v.z()}; };
        j["workspace"] = {{"frame", r.box->frame_name},
                          {"point", vec(r.box->frame.point_in_frame())},
                          {"box", o.workspace_box},
                          {"start", vec(r.box->start)},
                          {"min", vec(d.workspace->min)},
                          {"max", vec(d.workspace->max)},
                          {"margin", r.margin}};
    }
    return j;
}

void print_outcome(const Outcome& r) {
    const ExciteOptions& o = r.o;
    const excite::Design& d = r.d;
    fmt::print(stderr, "excite: {} {:.6g}, cond {:.4g} in {:.1f} s ({} evaluations); largest limit use {:.3f} (joint {} {})\n", o.criterion, d.criterion, d.cond,
               d.seconds, d.evaluations, d.check.worst, d.check.worst_joint + 1, excite::to_string(d.check.worst_kind));
    if (r.box) {
        fmt::print(stderr, "excite: workspace point of frame {}: x [{:.4f}, {:.4f}], y [{:.4f}, {:.4f}], z [{:.4f}, {:.4f}] m; closest to the box: {:.4f} m ({} face)\n",
                   r.box->frame_name, d.workspace->min.x(), d.workspace->max.x(), d.workspace->min.y(), d.workspace->max.y(), d.workspace->min.z(),
                   d.workspace->max.z(), r.margin, excite::face_name(r.closest));
    }
    const excite::Prediction* compared = r.compared_prediction ? &*r.compared_prediction : nullptr;
    fmt::print(stderr, "excite: predicted std of the {} over {:g} s (noise: {}){}:\n{}",
               r.payload ? fmt::format("payload's ten parameters about link {}'s frame (jacobid payload's WLS estimate, the arm held known)", r.payload->link)
                         : std::string("WLS estimate"),
               o.duration, r.prior.noise_source,
               r.compared ? fmt::format(", beside --compare {} ({:g} s, {})", o.compare, r.compared->duration, r.compared->how) : std::string(),
               prediction_table(r.names, r.target, r.predicted, compared));
    if (r.payload) fmt::print(stderr, "{}", payload_table(r.inertial_std, r.compared ? &r.compared_inertial_std : nullptr));
    fmt::print(stderr, "excite: after identify's F_p at {:.3g} Hz (what its decimated rows keep; the JSON's std_after_fp): worst relative std {:.3g} % ({})\n",
               r.bandwidth.decimation_cutoff_hz(), 100.0 * r.after_fp.worst_relative_std, r.worst_name(r.after_fp));
    fmt::print(stderr, "excite: worst relative std {:.3g} % ({}){}\n", 100.0 * r.predicted.worst_relative_std, r.worst_name(r.predicted),
               compared ? fmt::format("; --compare: {:.3g} % ({})", 100.0 * compared->worst_relative_std, r.worst_name(*compared)) : std::string());
    if (std::isfinite(r.predicted.reference_rms)) {
        fmt::print(stderr, "excite: predicted rms error of the model's torque over the reference ({}), in each joint's noise std, the joints summed in "
                   "quadrature: {:.4g}{}\n",
                   reference_name(o), r.predicted.reference_rms,
                   compared ? fmt::format("; --compare: {:.4g}", compared->reference_rms) : std::string());
    }
}

void run(ExciteOptions o) {
    resolve_payload_options(o);
    const robot::RobotDescription robot = robot::load_robot_description(o.robot);
    std::vector<NamedPath> inputs = robot_files("--robot", o.robot, robot);
    inputs.insert(inputs.end(), {{"--prior", o.prior}, {"--compare", o.compare}, {"--reference", o.reference}, {"--log-format", o.compare_format.file}});
    check_outputs({{"--output", o.output}, {"--json", o.json}, {"--plot", o.plot}}, inputs);
    const auto model = robot::make_robot_model(robot);
    const int n = model->joint_count();
    const ExcitePrior prior = resolve_prior(robot, *model, o.prior, o.torque_noise);
    // --payload: the design is for the payload's ten parameters, the arm held at the prior's values.
    std::optional<excite::PayloadTarget> payload;
    if (o.payload) payload = excite::make_payload_target(*model, o.payload_mass, o.payload_com);
    const ExcitePrior target = payload ? payload_prior(prior, *payload) : prior;
    const std::vector<std::string> names = payload ? payload->names : model->parameter_names();
    // The model's torque for the torque limits: the arm's prior, with the payload's when there is one.
    const Eigen::VectorXd x = payload ? excite::with_payload(prior.values, *payload) : prior.values;
    Eigen::VectorXd pose(n);
    const auto given_pose = per_joint(o.pose, static_cast<std::size_t>(n), std::numeric_limits<double>::quiet_NaN(), "--pose");
    const auto ranges = position_ranges(robot, o);
    for (int j = 0; j < n; ++j) {
        const auto k = static_cast<std::size_t>(j);
        pose[j] = std::isnan(given_pose[k]) ? 0.5 * (ranges[k].first + ranges[k].second) : given_pose[k];
    }
    const std::vector<excite::JointLimits> limits = joint_limits(robot, pose, o);
    resolve_frequencies(o, limits);
    check(o);
    excite::require_room_to_move(limits, pose, o.base_frequency, o.position_limit.empty() ? "the robot description" : "--position-limit");
    // The trajectory is sampled in memory (t and q, qd, qdd, tau per joint) and written as CSV (t, q, qd, qdd).
    refuse_oversized(fmt::format("--duration {:g} s at --rate {:g} Hz", o.duration, o.rate), std::floor(o.duration * o.rate) + 1.0, kMaxTrajectorySamples,
                     "trajectory samples", 8.0 * (1 + 4 * n) + 18.0 * (1 + 3 * n), "lower --duration or --rate");
    const std::optional<excite::Workspace> box = workspace(robot, pose, o);
    excite::ProblemSettings ps;
    ps.criterion = *excite::criterion_from_string(o.criterion);
    ps.information = {prior.noise_std, target.scales, 1.0, payload ? payload->projection : Eigen::MatrixXd(), {}, {}};
    if (ps.criterion == excite::Criterion::IOptimal) ps.information.reference = reference_information(robot, *model, limits, pose, prior, o);
    if (!o.reference.empty() && ps.criterion != excite::Criterion::IOptimal) {
        throw InputError(fmt::format("--reference {}: used by --criterion i-optimal only (the criterion is {})", o.reference, o.criterion));
    }
    ps.samples = o.samples;
    for (const auto route : {excite::DerivativeRoute::Adjoint, excite::DerivativeRoute::CentralDifferences, excite::DerivativeRoute::Automatic}) {
        if (o.derivatives == excite::to_string(route)) ps.derivatives = route;
    }
    excite::ExcitationProblem problem(*model, x, excite::FourierBasis(1.0 / o.base_frequency, o.harmonics, o.base_frequency), pose, limits, ps);
    // Each criterion sample stands for rate x duration / samples log samples (the information of the whole run).
    problem.set_sample_weight(o.rate * o.duration / problem.samples());
    if (o.decimation_cutoff > 0.0) problem.set_decimation_cutoff(o.decimation_cutoff);
    problem.set_workspace(box);
    if (!o.quiet) {
        fmt::print(stderr, "excite: {} joints x {} harmonics of {:g} Hz{} = {} coefficients, {}, {} samples per {:g} s period; criterion {}; noise {}; prior {}; {} "
                   "starts, {} s limit\n",
                   n, o.harmonics, o.base_frequency, o.base_frequency_text == "auto" || o.harmonics_text == "auto" ? " (auto)" : "", problem.variables(),
                   payload ? fmt::format("the payload's 10 parameters ({:g} kg expected; the arm's {} base parameters held)", payload->mass, model->parameter_count())
                           : fmt::format("{} base parameters", model->parameter_count()),
                   problem.samples(), 1.0 / o.base_frequency,
                   o.decimation_cutoff > 0.0 ? fmt::format("{} after F_p at {:g} Hz", o.criterion, o.decimation_cutoff) : o.criterion, prior.noise_source, prior.values_source, o.starts, o.time_limit);
        for (const auto& name : prior.fallbacks) fmt::print(stderr, "excite: --prior: {} was not identified there: the description's value is its prior\n", name);
    }
    excite::DesignSettings ds;
    ds.starts = o.starts;
    ds.threads = o.threads;
    ds.time_limit = o.time_limit;
    ds.max_evaluations = o.max_evaluations;
    ds.seed = o.seed;
    ds.control_rate = o.rate;
    if (!o.quiet) ds.progress = [](const std::string& line) { fmt::print(stderr, "excite: {}\n", line); };
    const excite::Design d = excite::design_excitation(problem, *model, x, limits, ds);
    excite::require_separable_design(d);
    const excite::FourierTrajectory trajectory = problem.trajectory(d.coefficients);
    const Sampled s = sample(trajectory, *model, x, o.duration, o.rate, box);
    Outcome r{o, *model, prior, target, names, payload, limits, pose, box, problem, d, trajectory, {}, {}, {}, {}, {}, {}, {}};
    // The prediction from every control sample (not the optimizer's), the same way as --compare's.
    auto predict_from = [&](const Eigen::MatrixXd& information, Eigen::VectorXd* inertial_std) {
        if (!payload) return excite::predict(information, prior.scales, ps.information.reference.size() > 0 ? &ps.information.reference : nullptr);
        if (inertial_std) *inertial_std = excite::predicted_inertial_std(information, *payload);
        return excite::predict_payload(information, *payload);
    };
    auto predict = [&](const excite::SampledMotion& motion, Eigen::VectorXd& inertial_std) {
        return predict_from(excite::motion_information(*model, motion, prior.noise_std), &inertial_std);
    };
    r.predicted = predict(motion_of(s), r.inertial_std);
    r.bandwidth = excite::identification_bandwidth(s.q, s.tau, prior.noise_std, o.rate);
    // The same after identify's F_p (a column's content above it is filtered out of both sides of its equations);
    // an F_p at or above the Nyquist frequency filters nothing.
    const double fp = r.bandwidth.decimation_cutoff_hz();
    r.after_fp = fp > 0.0 && fp < 0.45 * o.rate
                     ? predict_from(excite::filtered_motion_information(*model, motion_of(s), prior.noise_std, 1.0 / o.rate, fp), nullptr)
                     : r.predicted;
    // Said only when identify's automatic cutoff would miss the torque's band by a margin worth a flag (its rule
    // takes the torque's band: only if something, e.g. its position-noise limit, held it lower).
    r.needs_cutoff = r.bandwidth.recommended_cutoff_hz() > 1.5 * r.bandwidth.default_cutoff_hz();
    if (!o.compare.empty()) {
        r.compared = read_compare_motion(o.compare, robot, *model, o.compare_format, o.quiet);
        r.compared_prediction = predict(r.compared->motion, r.compared_inertial_std);
    }
    for (int f = 0; box && f < excite::kBoxFaces; ++f) {
        const int a = f / 2;
        const double distance = f % 2 == 0 ? box->box.upper[a] - d.workspace->max[a] : d.workspace->min[a] - box->box.lower[a];
        if (distance < r.margin) r.margin = distance, r.closest = f;
    }
    const double score = prediction_score(ps.criterion, r.predicted);
    r.worse = r.compared_prediction && score > prediction_score(ps.criterion, *r.compared_prediction);
    write_output(o.output, csv(s));
    if (!o.json.empty()) write_output(o.json, outcome_json(r).dump(2) + "\n");
    if (!o.plot.empty()) plot(o.plot, s, box, names, r.predicted, r.compared_prediction ? &*r.compared_prediction : nullptr, payload.has_value());
    if (!o.quiet) print_outcome(r);
    if (r.needs_cutoff) {
        // Said even with --quiet, like the warning below: with identify's defaults this design is identified badly.
        fmt::print(stderr,
                   "excite: identify this trajectory with --cutoff {:.3g}: its model torque holds 99 % of its energy below {:.3g} Hz (velocity {:.3g} Hz), "
                   "while identify's automatic differentiators would sit at {:.3g} Hz (held there by its position-noise limit) and bias the estimate "
                   "(docs/excite.md)\n",
                   r.bandwidth.recommended_cutoff_hz(), r.bandwidth.torque_hz, r.bandwidth.velocity_hz, r.bandwidth.default_cutoff_hz());
    }
    // Said even with --quiet: a design that does not beat the user's own trajectory must not pass unnoticed.
    if (r.worse) {
        fmt::print(stderr,
                   "excite: warning: the design is worse than --compare {} by its own criterion ({}: {:.6g} against {:.6g}); worst relative std {:.3g} % ({}) "
                   "against {:.3g} %\n",
                   o.compare, o.criterion, score, prediction_score(ps.criterion, *r.compared_prediction), 100.0 * r.predicted.worst_relative_std,
                   r.predicted.worst >= 0 ? names[static_cast<std::size_t>(r.predicted.worst)] : "-", 100.0 * r.compared_prediction->worst_relative_std);
    }
}

}  // namespace

void add_excite_command(CLI::App& app) {
    auto o = std::make_shared<ExciteOptions>();
    CLI::App* cmd = app.add_subcommand("excite",
                                       "design an excitation trajectory: finite Fourier series per joint, at rest at a pose at both ends of every period, "
                                       "optimized for the information of the base parameters within the joints' limits; predicts every base "
                                       "parameter's std, beside that of --compare");
    cmd->add_option("--robot", o->robot, "robot description (YAML): model, joint position limits, parameters (the prior without --prior)")->required()->check(file_path());
    cmd->add_option("--output,-o", o->output, "trajectory CSV at --rate: t, q1.., qd1.., qdd1.. ('-': standard output)")->capture_default_str()->check(file_path(true));
    cmd->add_option("--json", o->json, "JSON: coefficients, criterion, cond, peak position/velocity/acceleration/torque and limit use per joint")->check(file_path(true));
    cmd->add_option("--plot", o->plot, "PNG: positions, velocities and the model's torques over the whole duration")->check(file_path());
    add_excite_options(cmd, *o);
    cmd->callback([o] { run(*o); });
}

}  // namespace jacobid::cli
