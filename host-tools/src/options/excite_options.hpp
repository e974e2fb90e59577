// SPDX-License-Identifier: MIT
#pragma once
// jacobid excite's options (docs/excite.md), declared once: the command line's (cli/excite_command.cpp), their
// checks, and what they resolve to (the pose's limits, the automatic frequencies, the workspace box). Compiled
// with the excite library (it needs NLopt): a build without it has no excite command.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "excite/excitation_problem.hpp"
#include "excite/workspace_box.hpp"
#include "options/log_format_options.hpp"
#include "robot/robot_description.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace jacobid::options {

struct ExciteOptions {
    std::string robot;
    double duration = 20.0;
    std::string harmonics_text = "auto", base_frequency_text = "auto";  // "auto" or a number (resolve_frequencies)
    int harmonics = 5;
    double base_frequency = 0.1;
    std::string criterion = "d-optimal";
    std::string derivatives = "adjoint";
    std::string prior, compare;
    std::string reference;  // i-optimal: the motion the model will serve (empty: random moves within the limits)
    std::vector<double> torque_noise;
    std::vector<std::string> position_limit;  // LOWER:UPPER, one or one per joint
    LogFormatOptions compare_format;
    std::string output = "-";
    std::string json;
    std::string plot;
    std::vector<double> pose, velocity_limit, acceleration_limit, torque_limit;
    double rate = 1000.0;
    int samples = 0;
    // --decimation-cutoff: "off" (the criteria of every sample's regressor), "auto" (5 x the highest harmonic) or Hz;
    // decimation_cutoff is the resolved Hz (0: off).
    std::string decimation_cutoff_text = "off";
    double decimation_cutoff = 0.0;
    int starts = 4;
    int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    double time_limit = 60.0;
    int max_evaluations = 3000;  // per optimizer run (excite/excitation_design.hpp)
    std::uint64_t seed = 1;
    bool quiet = false;
    // Optional workspace box (excite/workspace_box.hpp): all three or none (the point defaults to the origin).
    std::string workspace_frame;
    std::vector<double> workspace_point, workspace_box;
    // --payload (excite/payload_target.hpp): a design for the ten inertial parameters of a payload on the last
    // link, the arm held known; its prior a point mass of --payload-mass at --payload-com.
    bool payload = false;
    double payload_mass = 0.0;
    std::vector<double> payload_com{0.0, 0.0, 0.0};
    const CLI::Option* duration_option = nullptr;  // whether --duration was given (--payload's default is kPayloadDuration)
    const CLI::Option* payload_mass_option = nullptr;
    const CLI::Option* payload_com_option = nullptr;
};

// --payload's default --duration, s: two periods of 5 s, short enough to repeat for every tool change.
constexpr double kPayloadDuration = 10.0;

// Every option but the command's own files' (--robot, --output, --json, --plot are declared by the command too).
void add_excite_options(CLI::App* command, ExciteOptions& o);

// Per joint, the position range: the description's limits, or --position-limit's.
std::vector<std::pair<double, double>> position_ranges(const robot::RobotDescription& robot, const ExciteOptions& o);
// Per joint, the limits the design keeps (InputError naming the option for a bad one, or a pose outside them).
std::vector<excite::JointLimits> joint_limits(const robot::RobotDescription& robot, const Eigen::VectorXd& pose, const ExciteOptions& o);
// --base-frequency and --harmonics: "auto" (excite/frequency_rule.hpp) or a number.
void resolve_frequencies(ExciteOptions& o, const std::vector<excite::JointLimits>& limits);
// The options against each other once the frequencies are resolved (one-line InputError naming the option).
void check(const ExciteOptions& o);
// --payload's options together (--payload-mass needed, neither without --payload), and its default --duration.
void resolve_payload_options(ExciteOptions& o);
// The workspace options given together, or none; the workspace they describe (null: none).
std::optional<excite::Workspace> workspace(const robot::RobotDescription& robot, const Eigen::VectorXd& pose, const ExciteOptions& o);

// The samples a trajectory may have in memory (t, q, qd, qdd, tau per joint).
constexpr double kMaxTrajectorySamples = 1e8;

}  // namespace jacobid::options
