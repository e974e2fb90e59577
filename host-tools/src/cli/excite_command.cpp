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
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <thread>
#include <nlohmann/json.hpp>

#include "cli/command.hpp"
#include "cli/excite_prediction.hpp"
#include "options/log_format_options.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"
#include "options/robot_files.hpp"
#include "core/per_joint.hpp"
#include "excite/design_checks.hpp"
#include "excite/excitation_design.hpp"
#include "excite/frequency_rule.hpp"
#include "excite/identification_bandwidth.hpp"
#include "excite/motion_information.hpp"
#include "plot/gnuplot.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::cli {
namespace {

struct ExciteOptions {
    std::string robot;
    double duration = 20.0;
    std::string harmonics_text = "auto", base_frequency_text = "auto";  // "auto" or a number (resolve_frequencies)
    int harmonics = 5;
    double base_frequency = 0.1;
    std::string criterion = "d-optimal";
    std::string derivatives = "adjoint";
    std::string prior, compare;
    std::vector<double> torque_noise;
    std::vector<std::string> position_limit;  // LOWER:UPPER, one or one per joint
    LogFormatOptions compare_format;
    std::string output = "-";
    std::string json;
    std::string plot;
    std::vector<double> pose, velocity_limit, acceleration_limit, torque_limit;
    double rate = 1000.0;
    int samples = 0;
    int starts = 4;
    int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    double time_limit = 60.0;
    std::uint64_t seed = 1;
    bool quiet = false;
    // Optional workspace box (excite/workspace_box.hpp): all three or none (the point defaults to the origin).
    std::string workspace_frame;
    std::vector<double> workspace_point, workspace_box;
};

// "LOWER:UPPER" (rad) of --position-limit for joint j (0-based).
std::pair<double, double> position_range(const std::string& text, int j) {
    const auto colon = text.find(':');
    double lower = std::numeric_limits<double>::quiet_NaN(), upper = lower;
    try {
        if (colon != std::string::npos) {
            std::size_t used = 0;
            lower = std::stod(text.substr(0, colon), &used);
            if (used != colon) lower = std::numeric_limits<double>::quiet_NaN();
            const std::string rest = text.substr(colon + 1);
            upper = std::stod(rest, &used);
            if (used != rest.size()) upper = std::numeric_limits<double>::quiet_NaN();
        }
    } catch (const std::exception&) {
    }
    if (!std::isfinite(lower) || !std::isfinite(upper) || !(lower < upper)) {
        throw InputError(fmt::format("--position-limit: joint {}: '{}': expected LOWER:UPPER in rad with LOWER < UPPER", j + 1, text));
    }
    return {lower, upper};
}

// Per joint, the position range: the description's limits, or --position-limit's.
std::vector<std::pair<double, double>> position_ranges(const robot::RobotDescription& robot, const ExciteOptions& o) {
    const int n = static_cast<int>(robot.joints.size());
    if (o.position_limit.size() > 1 && static_cast<int>(o.position_limit.size()) != n) {
        throw InputError(fmt::format("--position-limit: {} ranges for a robot with {} joints (give one LOWER:UPPER or one per joint)", o.position_limit.size(), n));
    }
    std::vector<std::pair<double, double>> ranges;
    for (int j = 0; j < n; ++j) {
        const auto& jd = robot.joints[static_cast<std::size_t>(j)];
        ranges.push_back(o.position_limit.empty() ? std::pair{jd.lower_limit, jd.upper_limit}
                                                  : position_range(o.position_limit[o.position_limit.size() == 1 ? 0 : static_cast<std::size_t>(j)], j));
    }
    return ranges;
}

std::vector<excite::JointLimits> joint_limits(const robot::RobotDescription& robot, const Eigen::VectorXd& pose, const ExciteOptions& o) {
    const int n = static_cast<int>(robot.joints.size());
    const auto v = per_joint(o.velocity_limit, static_cast<std::size_t>(n), std::numeric_limits<double>::infinity(), "--velocity-limit");
    const auto a = per_joint(o.acceleration_limit, static_cast<std::size_t>(n), std::numeric_limits<double>::infinity(), "--acceleration-limit");
    const auto t = per_joint(o.torque_limit, static_cast<std::size_t>(n), std::numeric_limits<double>::infinity(), "--torque-limit");
    const auto ranges = position_ranges(robot, o);
    std::vector<excite::JointLimits> limits(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) {
        auto& l = limits[static_cast<std::size_t>(j)];
        std::tie(l.lower, l.upper) = ranges[static_cast<std::size_t>(j)];
        l.velocity = v[static_cast<std::size_t>(j)], l.acceleration = a[static_cast<std::size_t>(j)], l.torque = t[static_cast<std::size_t>(j)];
        if (!(pose[j] > l.lower && pose[j] < l.upper)) {
            throw InputError(fmt::format("--pose: joint {} at {} rad is not strictly inside its limits [{}, {}] ({})", j + 1, pose[j], l.lower,
                                         l.upper, o.position_limit.empty() ? "robot description" : "--position-limit"));
        }
        for (const auto& [value, name] : {std::pair{l.velocity, "--velocity-limit"}, {l.acceleration, "--acceleration-limit"}, {l.torque, "--torque-limit"}}) {
            if (!(value > 0.0)) throw InputError(fmt::format("{}: joint {} limit {}: expected > 0", name, j + 1, value));
        }
    }
    return limits;
}

// The samples a trajectory may have in memory (t, q, qd, qdd, tau per joint).
constexpr double kMaxTrajectorySamples = 1e8;

void check(const ExciteOptions& o) {
    if (!(o.base_frequency > 0.0) || !std::isfinite(o.base_frequency)) throw InputError(fmt::format("--base-frequency {}: expected > 0 Hz", o.base_frequency));
    if (o.harmonics < 1 || o.harmonics > 50) throw InputError(fmt::format("--harmonics {}: expected 1 .. 50", o.harmonics));
    const double period = 1.0 / o.base_frequency, periods = o.duration / period;
    if (!(o.duration > 0.0) || std::abs(periods - std::round(periods)) > 1e-9 * periods || std::round(periods) < 1.0) {
        throw InputError(fmt::format("--duration {}: expected a whole number of periods of 1 / --base-frequency = {} s", o.duration, period));
    }
    // The period's samples follow from the base frequency (given, or automatic from --duration): a bad one is
    // named as such, not as a --rate without a whole number of samples per period (issue 36).
    const double samples_per_period = period * o.rate;
    const std::string base = o.base_frequency_text == "auto"
                                 ? fmt::format("the automatic base frequency {:g} Hz (--duration {:g} s in {:g} periods)", o.base_frequency, o.duration, std::round(periods))
                                 : fmt::format("--base-frequency {:g} Hz", o.base_frequency);
    if (samples_per_period > kMaxTrajectorySamples) {
        throw InputError(fmt::format("{}: a period of {:g} s is {:.3g} samples at --rate {:g} Hz, more than the {:g} a trajectory may have; raise "
                                     "--base-frequency",
                                     base, period, samples_per_period, o.rate, kMaxTrajectorySamples));
    }
    if (samples_per_period < 2 * o.harmonics + 1) {
        throw InputError(fmt::format("{}: a period of {:g} s holds {:.3g} samples at --rate {:g} Hz, fewer than 2 x {} harmonics + 1 = {} (the highest "
                                     "harmonic would alias); {} or raise --rate",
                                     base, period, samples_per_period, o.rate, o.harmonics, 2 * o.harmonics + 1,
                                     o.base_frequency_text == "auto" ? "lengthen --duration" : "lower --base-frequency"));
    }
    if (!(o.rate > 0.0) || std::abs(period * o.rate - std::round(period * o.rate)) > 1e-6) {
        throw InputError(fmt::format("--rate {}: expected a rate with a whole number of samples per period ({} s)", o.rate, period));
    }
    if (o.threads < 1) throw InputError(fmt::format("--threads {}: expected >= 1", o.threads));
    if (o.starts < 1) throw InputError(fmt::format("--starts {}: expected >= 1", o.starts));
    if (!(o.time_limit > 0.0)) throw InputError(fmt::format("--time-limit {}: expected > 0 s", o.time_limit));
    if (o.samples < 0) throw InputError(fmt::format("--samples {}: expected >= 0 (0: automatic)", o.samples));
    // Fewer samples per period than 2 x harmonics + 1 alias the highest harmonic: the optimizer's constraints
    // are then blind to where the trajectory peaks, and the tightening rounds chase crossings they cannot see.
    if (o.samples > 0 && o.samples < 2 * o.harmonics + 1) {
        throw InputError(fmt::format("--samples {}: expected 0 (automatic) or at least 2 x --harmonics + 1 = {} samples per period (fewer "
                                     "cannot see the highest harmonic)",
                                     o.samples, 2 * o.harmonics + 1));
    }
}

// The workspace options given together, or none; the workspace they describe (null: none).
std::optional<excite::Workspace> workspace(const robot::RobotDescription& robot, const Eigen::VectorXd& pose, const ExciteOptions& o) {
    const bool frame = !o.workspace_frame.empty(), box = !o.workspace_box.empty(), point = !o.workspace_point.empty();
    if (!frame && !box && !point) return std::nullopt;
    if (!frame) throw InputError(fmt::format("{}: needs --workspace-frame (the frame whose point the box holds)", box ? "--workspace-box" : "--workspace-point"));
    if (!box) throw InputError("--workspace-frame: needs --workspace-box xmin,xmax,ymin,ymax,zmin,zmax (m, base frame)");
    return excite::make_workspace(robot, o.workspace_frame, point ? o.workspace_point : std::vector<double>{0.0, 0.0, 0.0}, o.workspace_box, pose);
}

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
          const excite::Prediction& predicted, const excite::Prediction* compared) {
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
    plot::Panel prediction{"predicted relative std of each base parameter (WLS, std / prior scale)", "base parameter", "relative std (%)", false, true, {}, ""};
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

// --base-frequency and --harmonics: "auto" (excite/frequency_rule.hpp) or a number.
void resolve_frequencies(ExciteOptions& o, const std::vector<excite::JointLimits>& limits) {
    auto number = [](const std::string& text, const char* option, const char* expected) {
        std::size_t used = 0;
        double v = std::numeric_limits<double>::quiet_NaN();
        try {
            v = std::stod(text, &used);
        } catch (const std::exception&) {
        }
        if (used != text.size() || !std::isfinite(v)) throw InputError(fmt::format("{} '{}': expected auto or {}", option, text, expected));
        return v;
    };
    o.base_frequency = o.base_frequency_text == "auto" ? excite::auto_base_frequency(o.duration, limits)
                                                       : number(o.base_frequency_text, "--base-frequency", "a frequency > 0 Hz");
    if (!(o.base_frequency > 0.0)) throw InputError(fmt::format("--base-frequency {}: expected auto or a frequency > 0 Hz", o.base_frequency_text));
    if (o.harmonics_text == "auto") {
        o.harmonics = excite::auto_harmonics(o.base_frequency, limits);
    } else {
        const double h = number(o.harmonics_text, "--harmonics", "a whole number 1 .. 50");
        if (h != std::round(h) || h < 1 || h > 50) throw InputError(fmt::format("--harmonics {}: expected auto or a whole number 1 .. 50", o.harmonics_text));
        o.harmonics = static_cast<int>(h);
    }
}

// The trajectory at every control sample as a motion (excite/motion_information.hpp).
excite::SampledMotion motion_of(const Sampled& s) { return {s.q, s.qd, s.qdd, 0, 0}; }

void run(ExciteOptions o) {
    const robot::RobotDescription robot = robot::load_robot_description(o.robot);
    std::vector<NamedPath> inputs = robot_files("--robot", o.robot, robot);
    inputs.insert(inputs.end(), {{"--prior", o.prior}, {"--compare", o.compare}, {"--log-format", o.compare_format.file}});
    check_outputs({{"--output", o.output}, {"--json", o.json}, {"--plot", o.plot}}, inputs);
    const auto model = robot::make_robot_model(robot);
    const int n = model->joint_count();
    const ExcitePrior prior = resolve_prior(robot, *model, o.prior, o.torque_noise);
    const Eigen::VectorXd& x = prior.values;  // the model's torque for the torque limits, and the prior scales
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
    ps.information = {prior.noise_std, prior.scales, 1.0};
    ps.samples = o.samples;
    for (const auto route : {excite::DerivativeRoute::Adjoint, excite::DerivativeRoute::CentralDifferences, excite::DerivativeRoute::Automatic}) {
        if (o.derivatives == excite::to_string(route)) ps.derivatives = route;
    }
    excite::ExcitationProblem problem(*model, x, excite::FourierBasis(1.0 / o.base_frequency, o.harmonics, o.base_frequency), pose, limits, ps);
    // Each criterion sample stands for rate x duration / samples log samples (the information of the whole run).
    problem.set_sample_weight(o.rate * o.duration / problem.samples());
    problem.set_workspace(box);
    if (!o.quiet) {
        fmt::print(stderr, "excite: {} joints x {} harmonics of {:g} Hz{} = {} coefficients, {} base parameters, {} samples per {:g} s period; criterion {}; "
                   "noise {}; prior {}; {} starts, {} s limit\n",
                   n, o.harmonics, o.base_frequency, o.base_frequency_text == "auto" || o.harmonics_text == "auto" ? " (auto)" : "", problem.variables(),
                   model->parameter_count(), problem.samples(), 1.0 / o.base_frequency, o.criterion, prior.noise_source, prior.values_source, o.starts,
                   o.time_limit);
        for (const auto& name : prior.fallbacks) fmt::print(stderr, "excite: --prior: {} was not identified there: the description's value is its prior\n", name);
    }
    excite::DesignSettings ds;
    ds.starts = o.starts;
    ds.threads = o.threads;
    ds.time_limit = o.time_limit;
    ds.seed = o.seed;
    ds.control_rate = o.rate;
    if (!o.quiet) ds.progress = [](const std::string& line) { fmt::print(stderr, "excite: {}\n", line); };
    const excite::Design d = excite::design_excitation(problem, *model, x, limits, ds);
    excite::require_separable_design(d);
    const excite::FourierTrajectory trajectory = problem.trajectory(d.coefficients);
    const Sampled s = sample(trajectory, *model, x, o.duration, o.rate, box);
    // The prediction from every control sample (not the optimizer's), the same way as --compare's.
    const excite::Prediction predicted = excite::predict(excite::motion_information(*model, motion_of(s), prior.noise_std), prior.scales);
    const excite::IdentificationBandwidth bandwidth = excite::identification_bandwidth(s.q, s.tau, prior.noise_std, o.rate);
    // Said only when identify's automatic cutoff would miss the torque's band by a margin worth a flag (its rule
    // takes the torque's band: only if something, e.g. its position-noise limit, held it lower).
    const bool needs_cutoff = bandwidth.recommended_cutoff_hz() > 1.5 * bandwidth.default_cutoff_hz();
    std::optional<CompareMotion> compared;
    std::optional<excite::Prediction> compared_prediction;
    if (!o.compare.empty()) {
        compared = read_compare_motion(o.compare, robot, *model, o.compare_format, o.quiet);
        compared_prediction = excite::predict(excite::motion_information(*model, compared->motion, prior.noise_std), prior.scales);
    }
    // The smallest distance from the point to a face over the trajectory (m), and that face.
    double margin = std::numeric_limits<double>::infinity();
    int closest = 0;
    for (int f = 0; box && f < excite::kBoxFaces; ++f) {
        const int a = f / 2;
        const double distance = f % 2 == 0 ? box->box.upper[a] - d.workspace->max[a] : d.workspace->min[a] - box->box.lower[a];
        if (distance < margin) margin = distance, closest = f;
    }
    const excite::Criterion criterion = ps.criterion;
    const bool worse = compared_prediction && prediction_score(criterion, predicted) > prediction_score(criterion, *compared_prediction);
    const std::string worse_line =
        worse ? fmt::format("excite: warning: the design is worse than --compare {} by its own criterion ({}: {:.6g} against {:.6g}); worst relative std {:.3g} % "
                            "({}) against {:.3g} %",
                            o.compare, o.criterion, prediction_score(criterion, predicted), prediction_score(criterion, *compared_prediction),
                            100.0 * predicted.worst_relative_std, predicted.worst >= 0 ? model->parameter_names()[static_cast<std::size_t>(predicted.worst)] : "-",
                            100.0 * compared_prediction->worst_relative_std)
              : std::string();
    write_output(o.output, csv(s));
    if (!o.json.empty()) {
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
        j["top_frequency"] = excite::top_frequency(limits);
        j["rate"] = o.rate;
        j["samples"] = problem.samples();
        j["pose"] = std::vector<double>(pose.data(), pose.data() + n);
        j["parameters"] = model->parameter_names();
        j["noise_std"] = std::vector<double>(prior.noise_std.data(), prior.noise_std.data() + n);
        j["noise_source"] = prior.noise_source;
        j["noise_known"] = prior.noise_known;
        j["prior"] = prior.values_source;
        j["predicted"] = prediction_json(model->parameter_names(), prior, predicted);
        j["predicted"]["score"] = prediction_score(criterion, predicted);
        if (compared) {
            j["compare"] = {{"file", o.compare}, {"how", compared->how}, {"duration", compared->duration}};
            j["compare"]["predicted"] = prediction_json(model->parameter_names(), prior, *compared_prediction);
            j["compare"]["predicted"]["score"] = prediction_score(criterion, *compared_prediction);
            j["compare"]["worst_relative_std_ratio"] = predicted.worst_relative_std / compared_prediction->worst_relative_std;
            j["compare"]["design_worse"] = worse;
        }
        j["identification"] = {{"velocity_bandwidth_hz", bandwidth.velocity_hz},
                               {"torque_bandwidth_hz", bandwidth.torque_hz},
                               {"automatic_bandwidth_hz", bandwidth.automatic_hz},
                               {"differentiator_bandwidth_hz", bandwidth.differentiator_hz},
                               {"default_cutoff_hz", bandwidth.default_cutoff_hz()},
                               {"recommended_cutoff_hz", bandwidth.recommended_cutoff_hz()},
                               {"identify_options", needs_cutoff ? fmt::format("--cutoff {:.3g}", bandwidth.recommended_cutoff_hz()) : std::string()}};
        j["evaluations"] = d.evaluations;
        j["starts"] = d.start_criteria;
        j["tightening_rounds"] = d.rounds;
        j["seconds"] = d.seconds;
        nlohmann::json joints = nlohmann::json::array();
        for (int k = 0; k < n; ++k) {
            std::vector<double> a, b;
            for (int l = 0; l < o.harmonics; ++l) {
                a.push_back(trajectory.coefficients(k, 2 * l));
                b.push_back(trajectory.coefficients(k, 2 * l + 1));
            }
            joints.push_back({{"a", a},
                              {"b", b},
                              {"max_position", d.check.peak(k, 0)},
                              {"min_position", d.check.peak(k, 1)},
                              {"peak_velocity", d.check.peak(k, 2)},
                              {"peak_acceleration", d.check.peak(k, 3)},
                              {"peak_torque", d.check.peak(k, 4)},
                              {"limit_use", {{"upper_position", d.check.ratio(k, 0)},
                                             {"lower_position", d.check.ratio(k, 1)},
                                             {"velocity", d.check.ratio(k, 2)},
                                             {"acceleration", d.check.ratio(k, 3)},
                                             {"torque", d.check.ratio(k, 4)}}}});
        }
        j["joints"] = joints;
        if (box) {
            auto vec = [](const Eigen::Vector3d& v) { return std::vector<double>{v.x(), v.y(), v.z()}; };
            j["workspace"] = {{"frame", box->frame_name},
                              {"point", vec(box->frame.point_in_frame())},
                              {"box", o.workspace_box},
                              {"start", vec(box->start)},
                              {"min", vec(d.workspace->min)},
                              {"max", vec(d.workspace->max)},
                              {"margin", margin}};
        }
        write_output(o.json, j.dump(2) + "\n");
    }
    if (!o.plot.empty()) plot(o.plot, s, box, model->parameter_names(), predicted, compared_prediction ? &*compared_prediction : nullptr);
    if (!o.quiet) {
        fmt::print(stderr, "excite: {} {:.6g}, cond {:.4g} in {:.1f} s ({} evaluations); largest limit use {:.3f} (joint {} {})\n", o.criterion, d.criterion,
                   d.cond, d.seconds, d.evaluations, d.check.worst, d.check.worst_joint + 1, excite::to_string(d.check.worst_kind));
        if (box) {
            fmt::print(stderr, "excite: workspace point of frame {}: x [{:.4f}, {:.4f}], y [{:.4f}, {:.4f}], z [{:.4f}, {:.4f}] m; closest to the box: {:.4f} m ({} face)\n",
                       box->frame_name, d.workspace->min.x(), d.workspace->max.x(), d.workspace->min.y(), d.workspace->max.y(), d.workspace->min.z(),
                       d.workspace->max.z(), margin, excite::face_name(closest));
        }
        fmt::print(stderr, "excite: predicted std of the WLS estimate over {:g} s (noise: {}){}:\n{}", o.duration, prior.noise_source,
                   compared ? fmt::format(", beside --compare {} ({:g} s, {})", o.compare, compared->duration, compared->how) : std::string(),
                   prediction_table(model->parameter_names(), prior, predicted, compared_prediction ? &*compared_prediction : nullptr));
        fmt::print(stderr, "excite: worst relative std {:.3g} % ({}){}\n", 100.0 * predicted.worst_relative_std,
                   predicted.worst >= 0 ? model->parameter_names()[static_cast<std::size_t>(predicted.worst)] : "not identifiable",
                   compared_prediction ? fmt::format("; --compare: {:.3g} % ({})", 100.0 * compared_prediction->worst_relative_std,
                                                     compared_prediction->worst >= 0 ? model->parameter_names()[static_cast<std::size_t>(compared_prediction->worst)]
                                                                                     : "not identifiable")
                                       : std::string());
    }
    if (needs_cutoff) {
        // Said even with --quiet, like the warning below: with identify's defaults this design is identified badly.
        fmt::print(stderr,
                   "excite: identify this trajectory with --cutoff {:.3g}: its model torque holds 99 % of its energy below {:.3g} Hz (velocity {:.3g} Hz), "
                   "while identify's automatic differentiators would sit at {:.3g} Hz (held there by its position-noise limit) and bias the estimate "
                   "(docs/excite.md)\n",
                   bandwidth.recommended_cutoff_hz(), bandwidth.torque_hz, bandwidth.velocity_hz, bandwidth.default_cutoff_hz());
    }
    // Said even with --quiet: a design that does not beat the user's own trajectory must not pass unnoticed.
    if (worse) fmt::print(stderr, "{}\n", worse_line);
}

}  // namespace

void add_excite_command(CLI::App& app) {
    auto o = std::make_shared<ExciteOptions>();
    CLI::App* cmd = app.add_subcommand("excite",
                                       "design an excitation trajectory: finite Fourier series per joint, at rest at a pose at both ends of every period, "
                                       "optimized for the information of the base parameters within the joints' limits; predicts every base "
                                       "parameter's std, beside that of --compare");
    cmd->add_option("--robot", o->robot, "robot description (YAML): model, joint position limits, parameters (the prior without --prior)")->required()->check(file_path());
    cmd->add_option("--duration", o->duration, "s: a whole number of periods (period = 1 / --base-frequency), played back to back")
        ->check(positive_number())
        ->capture_default_str();
    cmd->add_option("--harmonics", o->harmonics_text,
                    "harmonics per joint (2 coefficients each), or auto: up to the highest frequency at which a joint reaches its velocity limit "
                    "within its acceleration limit, max a / (2 pi v) (0.5 Hz without both), 3 .. 10")
        ->capture_default_str();
    cmd->add_option("--base-frequency", o->base_frequency_text,
                    "Hz: the fundamental, one period lasts 1 / f; or auto: the duration split into the fewest periods (>= 2) of at most 10 s, fewer "
                    "(down to 2) while a period holds fewer than 6 harmonics up to the limits' frequency")
        ->capture_default_str();
    cmd->add_option("--criterion", o->criterion,
                    "d-optimal (-log det of the noise-weighted information matrix of the base parameters), a-relative (sum of the predicted "
                    "relative variances), e-relative (their max), or, for comparison, cond / logdet of the column-scaled regressor")
        ->check(CLI::IsMember({"d-optimal", "a-relative", "e-relative", "cond", "logdet"}))
        ->capture_default_str();
    cmd->add_option("--prior", o->prior,
                    "an earlier identification (jacobid identify --format json): its parameters are the prior (torque limits, relative std) and "
                    "its per-joint residuals the noise")->check(file_path());
    cmd->add_option("--torque-noise", o->torque_noise, "N.m: std of the torque noise, one value or one per joint (overrides --prior's; default 1)")
        ->delimiter(',');
    cmd->add_option("--compare", o->compare,
                    "a trajectory (t, q1.., qd1.., qdd1..) or a recorded log (the description's columns, or --log-format): its predicted std "
                    "beside the design's")->check(file_path());
    cmd->add_option("--position-limit", o->position_limit, "rad: LOWER:UPPER, one range or one per joint (default: the description's limits)")
        ->delimiter(',');
    cmd->add_option("--output,-o", o->output, "trajectory CSV at --rate: t, q1.., qd1.., qdd1.. ('-': standard output)")->capture_default_str()->check(file_path(true));
    cmd->add_option("--json", o->json, "JSON: coefficients, criterion, cond, peak position/velocity/acceleration/torque and limit use per joint")->check(file_path(true));
    cmd->add_option("--plot", o->plot, "PNG: positions, velocities and the model's torques over the whole duration")->check(file_path());
    cmd->add_option("--pose", o->pose, "rad: the rest pose at both ends of each period, one value or one per joint (default: the middle of each joint's limits)")
        ->delimiter(',')
        ->check(finite_number());
    // The limits are checked per joint by joint_limits() (> 0, naming the joint; inf: none).
    cmd->add_option("--velocity-limit", o->velocity_limit, "rad/s: one value or one per joint (default: none)")->delimiter(',');
    cmd->add_option("--acceleration-limit", o->acceleration_limit, "rad/s^2: one value or one per joint (default: none)")->delimiter(',');
    cmd->add_option("--torque-limit", o->torque_limit, "N.m, on the model's torque (description's parameters): one value or one per joint (default: none)")
        ->delimiter(',');
    cmd->add_option("--rate", o->rate, "Hz: control rate of the CSV; every sample is checked against the limits")->check(positive_number())->capture_default_str();
    cmd->add_option("--samples", o->samples, "samples per period seen by the optimizer (0: 20 per period of the highest harmonic, at least 100)")
        ->check(whole_number_in(0, 1e6))
        ->capture_default_str();
    cmd->add_option("--derivatives", o->derivatives,
                    "the regressor's derivatives in the gradients: adjoint (reverse-mode Newton-Euler, serial robots), or for comparison central "
                    "(central differences, any model) or automatic (forward-mode automatic differentiation, serial robots)")
        ->check(CLI::IsMember({"adjoint", "central", "automatic"}))
        ->capture_default_str();
    cmd->add_option("--starts", o->starts, "random starts of the optimizer (the best feasible one is kept)")->check(whole_number_from(1))->capture_default_str();
    cmd->add_option("--time-limit", o->time_limit, "s for all starts together")->check(positive_number())->capture_default_str();
    cmd->add_option("--threads", o->threads, "starts optimized side by side (default: the machine's cores)")->check(whole_number_in(1, 4096))->capture_default_str();
    cmd->add_option("--seed", o->seed, "seed of the random starts")->check(whole_number_from(0))->capture_default_str();
    cmd->add_option("--workspace-frame", o->workspace_frame,
                    "keep a point of this frame inside --workspace-box: a joint number 1..n (the frame that moves with joint j's link), tool or last "
                    "(joint n's), or a URDF link name");
    cmd->add_option("--workspace-point", o->workspace_point, "m: x,y,z of the point in --workspace-frame (default 0,0,0)")->delimiter(',');
    cmd->add_option("--workspace-box", o->workspace_box, "m, base frame: xmin,xmax,ymin,ymax,zmin,zmax; the point at --pose must be strictly inside")
        ->delimiter(',');
    cmd->add_flag("--quiet", o->quiet, "no progress on stderr");
    add_log_format_options(cmd, o->compare_format);
    cmd->callback([o] { run(*o); });
}

}  // namespace jacobid::cli
