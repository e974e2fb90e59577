// SPDX-License-Identifier: MIT
#include "options/drive_gains_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>

#include "core/errors.hpp"
#include "options/option_checks.hpp"
#include "core/same_file.hpp"
#include "identify/drive_gains/drive_gains.hpp"
#include "identify/drive_gains/drive_gains_report.hpp"
#include "identify/plan/log_columns.hpp"
#include "io/log_format.hpp"

namespace jacobid::options {

void add_drive_gain_options(CLI::App* cmd, DriveGainOptions& o) {
    cmd->add_flag("--drive-gains", o.enabled,
                  "identify the drive gains (current to torque) with the dynamic parameters from --in (no payload) and --loaded (the same "
                  "robot with a payload of known --payload-mass on the last link): least squares with std, total least squares and the "
                  "physically constrained estimate, and the `gains:` line of a log-format file");
    cmd->add_option("--loaded", o.loaded, "with --drive-gains: the log with the payload (same format and robot as --in)")->check(file_path());
    o.payload_mass_option = cmd->add_option("--payload-mass", o.payload_mass, "with --drive-gains: the payload's mass (kg, > 0); it fixes the gains' scale")
                                ->check(positive_number());
    cmd->add_option("--payload-com", o.payload_com,
                    "with --drive-gains: the payload's centre of mass x,y,z (m) in the last link's frame (URDF: the last moving joint's "
                    "frame); identified when not given")
        ->delimiter(',')
        ->expected(3)
        ->check(finite_number());
    cmd->add_option("--payload-inertia", o.payload_inertia,
                    "with --drive-gains and --payload-com: the payload's inertia about its centre of mass, XX,XY,XZ,YY,YZ,ZZ (kg.m^2) in the "
                    "last link's axes; identified when not given")
        ->delimiter(',')
        ->expected(6)
        ->check(finite_number());
}

namespace {

// One log given as both runs (a link, a copy) has no payload torque to fix the gains' scale: every gain comes
// out ~1e-13 with a std of ~3, TLS nan, and a `gains:` line ready to paste (issue 36). Refused by file before
// reading, by content after.
void refuse_same_file(const std::string& unloaded, const std::string& loaded) {
    if (!same_file(unloaded, loaded)) return;
    throw InputError(fmt::format("--loaded {}: is the file given to --in ({}); the gains' scale comes from the payload's torques: give the run "
                                 "with the payload as --loaded and the one without as --in", loaded, unloaded));
}

bool same_columns(const std::vector<const std::vector<double>*>& a, const std::vector<const std::vector<double>*>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t j = 0; j < a.size(); ++j) {
        if (*a[j] != *b[j]) return false;
    }
    return true;
}

void refuse_same_content(const identify::LogColumns& unloaded, const identify::LogColumns& loaded) {
    if (!same_columns(unloaded.q, loaded.q) || !same_columns(unloaded.tau, loaded.tau)) return;
    throw InputError(fmt::format("--loaded {}: holds exactly the positions and efforts of --in {} (a copy of the unloaded run?); the gains' scale "
                                 "comes from the payload's torques: give the run with the payload as --loaded",
                                 loaded.source, unloaded.source));
}

// A fit the logs do not determine (a loaded run without the payload's effect, a payload that barely loads
// the joints) is refused, never printed as gains: each least-squares gain must be finite and positive and
// known to better than 100 % (its std below its value), so that the `gains:` line is a measurement. A gain
// known to be negative is named as a sign (a gain is > 0, as the constrained estimate requires).
void refuse_undetermined_gains(const identify::DriveGainResult& r, const robot::RobotDescription& robot) {
    const identify::DriveGainEstimate& e = r.least_squares;
    for (Eigen::Index j = 0; j < e.gains.size(); ++j) {
        const double g = e.gains[j], s = e.std_dev[j];
        if (std::isfinite(g) && g > 0.0 && !(s >= g)) continue;
        const double prior = r.prior_gains[static_cast<std::size_t>(j)];
        if (std::isfinite(g) && g < 0.0 && s < -g) {
            throw InputError(fmt::format("--drive-gains: the gain of joint {} ({}) came out negative, {:.3g} (std {:.3g}): its effort column in --in {} "
                                         "and --loaded {} has the opposite sign of its torque (the joint's direction, or the sign of its gain in "
                                         "the log format)",
                                         j + 1, robot.joints[static_cast<std::size_t>(j)].name, g * prior, s * std::abs(prior), r.unloaded_source,
                                         r.loaded_source));
        }
        throw InputError(fmt::format(
            "--drive-gains: the gain of joint {} ({}) came out {:.3g} (std {:.3g}): --in {} and --loaded {} do not determine it (a gain must be "
            "positive and known to better than 100 %); is --loaded the run with the payload, and does its motion load joint {}?",
            j + 1, robot.joints[static_cast<std::size_t>(j)].name, g * prior, s * std::abs(prior), r.unloaded_source, r.loaded_source, j + 1));
    }
}

}  // namespace

std::string run_drive_gains(const robot::RobotDescription& robot, const robot::RobotModel& model, const DriveGainOptions& o, const FitOptions& fit,
                            const std::string& method, const DriveGainInputs& in) {
    if (o.loaded.empty()) throw InputError("--drive-gains needs --loaded LOG: the run with the payload");
    if (method == "both") throw InputError("--drive-gains with --method both: give one method");
    for (const auto& [option, given] : in.other_options) {
        if (given) throw InputError(fmt::format("--drive-gains with {}: not supported (write the gains into a log format, then identify with {})", option, option));
    }
    if (o.payload_mass_option == nullptr || o.payload_mass_option->count() == 0) {
        throw InputError("--drive-gains needs --payload-mass KG: the payload's mass, which fixes the gains' scale");
    }
    identify::PayloadKnowledge payload;
    payload.mass = o.payload_mass;
    if (!o.payload_com.empty()) payload.com = Eigen::Vector3d(o.payload_com[0], o.payload_com[1], o.payload_com[2]);
    if (!o.payload_inertia.empty()) payload.inertia = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(o.payload_inertia.data());
    identify::payload_parameters(payload);  // the options' errors before the logs are read

    refuse_same_file(in.in, o.loaded);

    const identify::Method m = method == "butterworth" ? identify::Method::Butterworth : identify::Method::Jacobi;
    const io::LogColumnNames names = robot_column_names(robot, in.time_column);
    const io::CsvTable unloaded_table = read_log_table(in.in, *in.log_format, names, in.quiet);
    const io::CsvTable loaded_table = [&] {
        try {
            return read_log_table(o.loaded, *in.log_format, names, in.quiet);
        } catch (const InputError& e) {
            throw InputError(fmt::format("--loaded {}", e.what()));
        }
    }();
    const identify::LogColumns unloaded = identify::log_columns(unloaded_table, robot, in.time_column, in.time_tolerance);
    const identify::LogColumns loaded = identify::log_columns(loaded_table, robot, in.time_column, in.time_tolerance);
    refuse_same_content(unloaded, loaded);
    identify::IdentifySettings settings = identify_settings(fit, m);
    settings.pipeline.method = m;
    if (identify::is_iterated(settings.estimator.estimator)) throw InputError("--drive-gains with --estimator iv|didim: use wls or ols");

    identify::DriveGainResult result = identify::identify_drive_gains(robot, model, unloaded, loaded, settings, payload);
    if (!in.log_format->file.empty()) {
        const io::LogFormat format = io::load_log_format(in.log_format->file);
        if (format.gains.size() == result.prior_gains.size()) result.prior_gains = format.gains;
    }
    refuse_undetermined_gains(result, robot);
    identify::ReportContext ctx;
    ctx.log_source = in.in;
    ctx.model_name = model.model_name();
    for (const auto& j : robot.joints) ctx.joint_names.push_back(j.name);
    return in.format == "json" ? identify::drive_gains_json(result, ctx).dump(2) + "\n" : identify::drive_gains_text(result, ctx);
}

}  // namespace jacobid::options
