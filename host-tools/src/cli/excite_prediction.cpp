// SPDX-License-Identifier: MIT
#include "cli/excite_prediction.hpp"

#include <fmt/core.h>

#include <cmath>

#include "core/errors.hpp"
#include "core/per_joint.hpp"
#include "excite/parameter_scales.hpp"
#include "excite/prior_file.hpp"
#include "identify/plan/log_columns.hpp"
#include "io/time_axis.hpp"
#include "io/csv_table.hpp"
#include "payload/payload_inertia.hpp"

namespace jacobid::cli {
namespace {

bool has_trajectory_columns(const io::CsvTable& table, int joints) {
    if (!table.has_column("t")) return false;
    for (int j = 1; j <= joints; ++j) {
        for (const char* kind : {"q", "qd", "qdd"}) {
            if (!table.has_column(fmt::format("{}{}", kind, j))) return false;
        }
    }
    return true;
}

}  // namespace

ExcitePrior resolve_prior(const robot::RobotDescription& robot, const robot::RobotModel& model, const std::string& prior_path,
                          const std::vector<double>& torque_noise) {
    const int n = model.joint_count();
    ExcitePrior p;
    p.values = robot::true_parameters(robot, model);
    p.values_source = "the robot description";
    p.noise_std = Eigen::VectorXd::Ones(n);
    p.noise_source = "unit (1 N.m per joint: give --torque-noise or --prior)";
    if (!prior_path.empty()) {
        const excite::PriorFile file = excite::read_prior_file(prior_path, model, p.values);
        p.values = file.values;
        p.noise_std = file.noise_std;
        p.values_source = p.noise_source = prior_path;
        p.noise_known = true;
        p.fallbacks = file.fallbacks;
    }
    if (!torque_noise.empty()) {
        const std::vector<double> noise = per_joint(torque_noise, static_cast<std::size_t>(n), 0.0, "--torque-noise");
        for (int j = 0; j < n; ++j) {
            const double s = noise[static_cast<std::size_t>(j)];
            if (!(s > 0.0) || !std::isfinite(s)) throw InputError(fmt::format("--torque-noise: joint {}: {} N.m: expected a finite std > 0", j + 1, s));
            p.noise_std[j] = s;
        }
        p.noise_source = "--torque-noise";
        p.noise_known = true;
    }
    p.scales = excite::prior_scales(robot, model, p.values);
    return p;
}

CompareMotion read_compare_motion(const std::string& path, const robot::RobotDescription& robot, const robot::RobotModel& model,
                                  const options::LogFormatOptions& format, bool quiet) {
    const int n = model.joint_count();
    const io::CsvTable table = format.file.empty() ? io::read_csv(path) : read_log_table(path, format, options::robot_column_names(robot, "t"), quiet);
    CompareMotion c;
    if (format.file.empty() && has_trajectory_columns(table, n)) {
        for (int j = 1; j <= n; ++j) {
            c.motion.q.push_back(table.column(fmt::format("q{}", j)));
            c.motion.qd.push_back(table.column(fmt::format("qd{}", j)));
            c.motion.qdd.push_back(table.column(fmt::format("qdd{}", j)));
        }
        const auto& t = table.column("t");
        if (t.size() < 2) throw InputError(fmt::format("--compare {}: {} rows: expected a trajectory of at least 2 rows", path, t.size()));
        c.duration = t.back() - t.front();
        c.how = "trajectory table (t, q, qd, qdd)";
        return c;
    }
    const identify::LogColumns log = identify::log_columns(table, robot, "t", io::kDefaultTimeTolerance);
    identify::PipelineSettings settings;
    identify::PipelineInfo info = identify::plan_pipeline(log, settings);
    const identify::StateEstimates states = identify::estimate_states(log, settings, info, &model);
    c.motion.q = states.q, c.motion.qd = states.qd, c.motion.qdd = states.qdd;
    c.motion.first = states.first, c.motion.last = states.last;
    c.duration = static_cast<double>(states.last - states.first) * log.sample_period;
    c.how = fmt::format("log, differentiated like identify (bandwidth {:.3g} Hz, Jacobi windows {:.3g} / {:.3g} s)", info.bandwidth, info.velocity_window,
                        info.acceleration_window);
    return c;
}

double prediction_score(excite::Criterion criterion, const excite::Prediction& p) {
    if (!p.identifiable) return excite::kRankDeficient;
    switch (criterion) {
        case excite::Criterion::DOptimal: return -p.log_det;
        case excite::Criterion::ARelative: return std::log(p.relative_std.squaredNorm());
        case excite::Criterion::IOptimal: return 2.0 * std::log(p.reference_rms);
        default: return 2.0 * std::log(p.worst_relative_std);
    }
}

nlohmann::json prediction_json(const std::vector<std::string>& names, const ExcitePrior& prior, const excite::Prediction& p) {
    auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
    nlohmann::json parameters = nlohmann::json::object();
    for (std::size_t k = 0; k < names.size(); ++k) {
        const auto i = static_cast<Eigen::Index>(k);
        parameters[names[k]] = {{"prior", prior.values[i]}, {"scale", prior.scales[i]}, {"std", number(p.std_dev[i])}, {"relative_std", number(p.relative_std[i])}};
    }
    return {{"identifiable", p.identifiable},
            {"log_det_information", p.identifiable ? nlohmann::json(p.log_det) : nlohmann::json()},
            {"worst_relative_std", number(p.worst_relative_std)},
            {"worst_parameter", p.worst >= 0 ? nlohmann::json(names[static_cast<std::size_t>(p.worst)]) : nlohmann::json()},
            {"reference_rms", number(p.reference_rms)},
            {"parameters", parameters}};
}

std::string prediction_table(const std::vector<std::string>& names, const ExcitePrior& prior, const excite::Prediction& design,
                             const excite::Prediction* compare) {
    std::string out = fmt::format("{:<10} {:>12} {:>11} {:>11} {:>9}", "parameter", "prior", "scale", "std", "rel std");
    if (compare) out += fmt::format(" {:>11} {:>9} {:>7}", "compare std", "rel std", "ratio");
    out += "\n";
    for (std::size_t k = 0; k < names.size(); ++k) {
        const auto i = static_cast<Eigen::Index>(k);
        out += fmt::format("{:<10} {:>12.5g} {:>11.3g} {:>11.3g} {:>8.3g}%", names[k], prior.values[i], prior.scales[i], design.std_dev[i], 100.0 * design.relative_std[i]);
        if (compare) {
            out += fmt::format(" {:>11.3g} {:>8.3g}% {:>7.3g}", compare->std_dev[i], 100.0 * compare->relative_std[i], design.std_dev[i] / compare->std_dev[i]);
        }
        out += "\n";
    }
    return out;
}

ExcitePrior payload_prior(const ExcitePrior& prior, const excite::PayloadTarget& payload) {
    ExcitePrior p = prior;
    p.values = payload.prior;
    p.scales = payload.scales;
    p.values_source = fmt::format("a point mass of {:g} kg at ({:g}, {:g}, {:g}) m in link {}'s frame (--payload-mass, --payload-com)", payload.mass, payload.com.x(),
                                  payload.com.y(), payload.com.z(), payload.link);
    return p;
}

nlohmann::json payload_json(const excite::PayloadTarget& payload, const Eigen::VectorXd& inertial_std, const Eigen::VectorXd* compare_inertial_std) {
    auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
    auto stds = [&](const Eigen::VectorXd& v) {
        nlohmann::json out = nlohmann::json::object();
        for (std::size_t k = 0; k < payload::inertial_names().size(); ++k) out[payload::inertial_names()[k]] = number(v[static_cast<Eigen::Index>(k)]);
        return out;
    };
    nlohmann::json j = {{"mass", payload.mass},
                        {"com", {payload.com.x(), payload.com.y(), payload.com.z()}},
                        {"link", payload.link},
                        {"parameters", payload.names},
                        {"prior", std::vector<double>(payload.prior.data(), payload.prior.data() + payload.prior.size())},
                        {"size", std::max(payload.com.norm(), excite::kPayloadMinSize)},
                        {"predicted_std", stds(inertial_std)}};
    if (compare_inertial_std) j["compare_predicted_std"] = stds(*compare_inertial_std);
    return j;
}

std::string payload_table(const Eigen::VectorXd& inertial_std, const Eigen::VectorXd* compare_inertial_std) {
    std::string out = fmt::format("excite: as jacobid payload prints them (about the centre of mass, at the prior):\n{:<10} {:>11}", "quantity", "std");
    if (compare_inertial_std) out += fmt::format(" {:>11} {:>7}", "compare std", "ratio");
    out += "\n";
    for (std::size_t k = 0; k < payload::inertial_names().size(); ++k) {
        const auto i = static_cast<Eigen::Index>(k);
        out += fmt::format("{:<10} {:>11.3g}", payload::inertial_names()[k], inertial_std[i]);
        if (compare_inertial_std) out += fmt::format(" {:>11.3g} {:>7.3g}", (*compare_inertial_std)[i], inertial_std[i] / (*compare_inertial_std)[i]);
        out += "\n";
    }
    return out;
}

}  // namespace jacobid::cli
