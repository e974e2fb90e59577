// SPDX-License-Identifier: MIT
#include "options/excite_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <tuple>

#include "core/errors.hpp"
#include "core/per_joint.hpp"
#include "excite/frequency_rule.hpp"
#include "options/option_checks.hpp"

namespace jacobid::options {
namespace {

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

}  // namespace

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
    if (o.max_evaluations < 1) throw InputError(fmt::format("--max-evaluations {}: expected >= 1", o.max_evaluations));
    if (o.samples < 0) throw InputError(fmt::format("--samples {}: expected >= 0 (0: automatic)", o.samples));
    // Fewer samples per period than 2 x harmonics + 1 alias the highest harmonic: the optimizer's constraints
    // are then blind to where the trajectory peaks, and the tightening rounds chase crossings they cannot see.
    if (o.samples > 0 && o.samples < 2 * o.harmonics + 1) {
        throw InputError(fmt::format("--samples {}: expected 0 (automatic) or at least 2 x --harmonics + 1 = {} samples per period (fewer "
                                     "cannot see the highest harmonic)",
                                     o.samples, 2 * o.harmonics + 1));
    }
}

std::optional<excite::Workspace> workspace(const robot::RobotDescription& robot, const Eigen::VectorXd& pose, const ExciteOptions& o) {
    const bool frame = !o.workspace_frame.empty(), box = !o.workspace_box.empty(), point = !o.workspace_point.empty();
    if (!frame && !box && !point) return std::nullopt;
    if (!frame) throw InputError(fmt::format("{}: needs --workspace-frame (the frame whose point the box holds)", box ? "--workspace-box" : "--workspace-point"));
    if (!box) throw InputError("--workspace-frame: needs --workspace-box xmin,xmax,ymin,ymax,zmin,zmax (m, base frame)");
    return excite::make_workspace(robot, o.workspace_frame, point ? o.workspace_point : std::vector<double>{0.0, 0.0, 0.0}, o.workspace_box, pose);
}

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
    // identify puts F_p at 5 x the motion's bandwidth (docs/method.md, "Motion bandwidth estimate"), which on a
    // design lies near its highest harmonic (the PUMA 560's 15 x 0.05 Hz design: 3.75 Hz against identify's 3.81 Hz
    // on it; its 7 x 0.1 Hz design: 3.5 Hz against 3.66 Hz).
    if (o.decimation_cutoff_text == "off") {
        o.decimation_cutoff = 0.0;
    } else if (o.decimation_cutoff_text == "auto") {
        o.decimation_cutoff = 5.0 * o.harmonics * o.base_frequency;
    } else {
        o.decimation_cutoff = number(o.decimation_cutoff_text, "--decimation-cutoff", "a frequency > 0 Hz, or off");
        if (!(o.decimation_cutoff > 0.0)) throw InputError(fmt::format("--decimation-cutoff {}: expected off, auto or a frequency > 0 Hz", o.decimation_cutoff_text));
    }
}

void add_excite_options(CLI::App* cmd, ExciteOptions& o_) {
    ExciteOptions* o = &o_;
    o->duration_option = cmd->add_option("--duration", o->duration, "s: a whole number of periods (period = 1 / --base-frequency), played back to back (--payload: 10)")
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
                    "relative variances), e-relative (their max), i-optimal (the predicted variance of the model's torque over --reference's "
                    "motion), or, for comparison, cond / logdet of the column-scaled regressor")
        ->check(CLI::IsMember({"d-optimal", "a-relative", "e-relative", "i-optimal", "cond", "logdet"}))
        ->capture_default_str();
    cmd->add_option("--prior", o->prior,
                    "an earlier identification (jacobid identify --format json): its parameters are the prior (torque limits, relative std) and "
                    "its per-joint residuals the noise")->check(file_path());
    cmd->add_option("--torque-noise", o->torque_noise, "N.m: std of the torque noise, one value or one per joint (overrides --prior's; default 1)")
        ->delimiter(',');
    cmd->add_option("--compare", o->compare,
                    "a trajectory (t, q1.., qd1.., qdd1..) or a recorded log (the description's columns, or --log-format): its predicted std "
                    "beside the design's")->check(file_path());
    cmd->add_option("--reference", o->reference,
                    "--criterion i-optimal: the motion the identified model will serve, a trajectory or a log as for --compare (default: 60 s of "
                    "random point-to-point moves within the design's position, velocity and acceleration limits, seed 1)")
        ->check(file_path());
    cmd->add_option("--position-limit", o->position_limit, "rad: LOWER:UPPER, one range or one per joint (default: the description's limits)")
        ->delimiter(',');
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
    cmd->add_option("--decimation-cutoff", o->decimation_cutoff_text,
                    "Hz: the information criteria of the regressor filtered as identify's decimation filter F_p at this cutoff will filter it "
                    "(its rows keep only that), or auto: 5 x the highest harmonic (identify's F_p is 5 x the motion's bandwidth), or off: every "
                    "sample's regressor as it is")
        ->capture_default_str();
    cmd->add_option("--derivatives", o->derivatives,
                    "the regressor's derivatives in the gradients: adjoint (reverse-mode Newton-Euler, serial robots), or for comparison central "
                    "(central differences, any model) or automatic (forward-mode automatic differentiation, serial robots)")
        ->check(CLI::IsMember({"adjoint", "central", "automatic"}))
        ->capture_default_str();
    cmd->add_option("--starts", o->starts, "random starts of the optimizer (the best feasible one is kept)")->check(whole_number_from(1))->capture_default_str();
    cmd->add_option("--time-limit", o->time_limit, "s for all starts together")->check(positive_number())->capture_default_str();
    cmd->add_option("--max-evaluations", o->max_evaluations,
                    "criterion evaluations per optimizer run (each start, restart and tightening round); when they, not --time-limit, end "
                    "every run, the design depends on --seed only, not on the machine's speed")
        ->check(whole_number_in(1, 1e9))
        ->capture_default_str();
    cmd->add_option("--threads", o->threads, "starts optimized side by side (default: the machine's cores)")->check(whole_number_in(1, 4096))->capture_default_str();
    cmd->add_option("--seed", o->seed, "seed of the random starts")->check(whole_number_from(0))->capture_default_str();
    cmd->add_option("--workspace-frame", o->workspace_frame,
                    "keep a point of this frame inside --workspace-box: a joint number 1..n (the frame that moves with joint j's link), tool or last "
                    "(joint n's), or a URDF link name");
    cmd->add_option("--workspace-point", o->workspace_point, "m: x,y,z of the point in --workspace-frame (default 0,0,0)")->delimiter(',');
    cmd->add_option("--workspace-box", o->workspace_box, "m, base frame: xmin,xmax,ymin,ymax,zmin,zmax; the point at --pose must be strictly inside")
        ->delimiter(',');
    cmd->add_flag("--payload", o->payload,
                  "design for the ten inertial parameters of a payload on the last link (what jacobid payload estimates), the arm held at the "
                  "description's (or --prior's) values: the criterion of the payload's information only; default --duration 10; needs --payload-mass");
    o->payload_mass_option = cmd->add_option("--payload-mass", o->payload_mass,
                                             "kg, with --payload: the payload's expected mass; the prior is a point mass there (the torque limits' model, the "
                                             "scales of the relative std)");
    o->payload_com_option = cmd->add_option("--payload-com", o->payload_com, "m, with --payload: x,y,z of the expected centre of mass in the last link's frame (default 0,0,0)")
                                ->delimiter(',');
    cmd->add_flag("--quiet", o->quiet, "no progress on stderr");
    add_log_format_options(cmd, o->compare_format);
}

void resolve_payload_options(ExciteOptions& o) {
    const bool mass = o.payload_mass_option && o.payload_mass_option->count() > 0, com = o.payload_com_option && o.payload_com_option->count() > 0;
    if (!o.payload) {
        if (mass || com) throw InputError(fmt::format("{}: only with --payload (a design for a payload's parameters)", mass ? "--payload-mass" : "--payload-com"));
        return;
    }
    // The relative std and the torque limits need the payload's size: its mass is what the user knows of it.
    if (!mass) throw InputError("--payload: needs --payload-mass KG (the payload's expected mass: the prior of the relative std and the torque limits)");
    if (!(o.duration_option && o.duration_option->count() > 0)) o.duration = kPayloadDuration;
}

}  // namespace jacobid::options
