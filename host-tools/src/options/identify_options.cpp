// SPDX-License-Identifier: MIT
#include "options/identify_options.hpp"

#include <CLI/CLI.hpp>

#include "options/model_export_options.hpp"
#include "options/option_checks.hpp"

namespace jacobid::options {

const std::string& IdentifyOptions::first_input() const {
    static const std::string none;
    return inputs.empty() ? none : inputs.front();
}

void add_identify_options(CLI::App* cmd, IdentifyOptions& o) {
    cmd->add_option("--piece-rows", o.piece_rows,
                    "rows of a long CSV log held at once (default 0: as many as fit in 400 MB of its kept columns, an hour of 1 kHz "
                    "6-axis data): a longer log is identified piece by piece, like the segments of --on-gap split, so memory does "
                    "not grow with the log")
        ->check(whole_number_from(0))
        ->capture_default_str();
    cmd->add_option("--threads", o.threads,
                    "threads (0: one per core): several logs (or --on-gap split segments) are processed at once, one log's regressor, "
                    "F_p and least squares are split over them; the results do not depend on it")
        ->capture_default_str();
    cmd->add_option("--method", o.method, "jacobi, butterworth, or both side by side")
        ->check(CLI::IsMember({"jacobi", "butterworth", "both"}))
        ->capture_default_str();
    cmd->add_option("--report", o.report, "also write DIR/report.md and PNG plots (torque measured vs model)")->check(file_path());
    cmd->add_option("--time-column", o.time_column, "name of the time column (s)")->capture_default_str();
    add_time_tolerance_option(cmd, o.time_tolerance);
    cmd->add_option("--can-config", o.can_config,
                    "jacobid-fw config (YAML) whose joints' CAN profiles, ids, gear ratios and torque constants decode --in and "
                    "--validate as candump -L captures instead of CSV")
        ->check(file_path());
    add_log_format_options(cmd, o.log_format);
    add_fit_options(cmd, o);
    cmd->add_option("--velocity", o.velocity,
                    "velocities of the regressor: measured (the log's velocity columns, qdJ or --log-format velocities), or jacobi / "
                    "butterworth (the positions differentiated; default: the --method's own differentiator)")
        ->check(CLI::IsMember({"measured", "jacobi", "butterworth"}));
    cmd->add_option("--essential", o.essential,
                    "essential parameters: drop the parameter with the largest %sigma_r above this threshold (%), re-identify, repeat")
        ->check(positive_number())
        ->each([&o](const std::string&) { o.essential_flag = true; })
        ->expected(0, 1)
        ->default_str("10");
    cmd->add_flag("--physical", o.physical,
                  "physically consistent parameters: every link's pseudo-inertia positive definite (positive mass, positive definite "
                  "inertia, triangle inequalities), rotor inertias and friction coefficients >= 0; the standard parameters nearest the "
                  "description's (URDF) values among those that fit the data, reported with the active constraints (mdh/urdf models)");
    cmd->add_flag("--semi-physical", o.semi_physical,
                  "as --physical without the triangle inequalities: positive mass and positive definite inertia about the centre of mass");
    cmd->add_option("--prior-weight", o.prior_weight,
                    "weight of the description's standard values in --physical: w sum ((s - prior) / unit)^2 beside the data's chi^2 "
                    "(units 0.01 kg.m^2, 0.1 kg.m, 1 kg, 1 N.m); it decides only what the log does not excite")
        ->check(non_negative_number())
        ->capture_default_str();
    add_model_export_options(cmd, o.model_export);
    add_drive_gain_options(cmd, o.drive_gains);
    cmd->add_option("--period", o.period,
                    "the log repeats one trajectory with this period (s, a whole number of samples), or 'auto' to detect it from the "
                    "positions: the whole periods are averaged (noise / sqrt(periods)), the period-to-period spread gives each joint's "
                    "noise for the weights, and the mean period is identified as a periodic signal (no edges lost)");
    cmd->add_flag("--quiet", o.quiet, "no progress messages on stderr");
}

void finish_identify_options(IdentifyOptions& o) {
    if (o.essential_flag && o.essential <= 0.0) o.essential = 10.0;
    o.pipeline.exact_discretization = o.discretization == "exact";
}

}  // namespace jacobid::options
