// SPDX-License-Identifier: MIT
// jacobid simulate: a closed-loop simulated robot log (t, q_j, tau_j) plus its truth (parameters and the
// noise-free states), the test bench of the identification pipeline.
#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.hpp"
#include "options/log_format_options.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"
#include "options/robot_files.hpp"
#include "options/simulation_options.hpp"
#include "robot/robot_description.hpp"
#include "robot/simulated_parameters.hpp"
#include "sim/augmented_model.hpp"
#include "sim/effect_spec.hpp"
#include "sim/external_torque.hpp"
#include "sim/simulator.hpp"
#include "sim/tabulated_trajectory.hpp"
#include "io/partial_output.hpp"
#include "identify/plan/log_columns.hpp"
#include "io/csv_table.hpp"

namespace jacobid::cli {
namespace {

// SimulationOptions: the run itself (simulation_options.hpp, shared with montecarlo).
struct SimulateOptions : SimulationOptions {
    std::string robot;
    std::string out;
    std::string truth;
    std::string states;
    std::vector<std::string> effects;  // --effect tokens
    std::string effects_file;
    std::string trajectory;          // --trajectory: a given reference instead of the random moves
    bool duration_given = false;     // --duration on the command line (else a --trajectory's length)
    bool quiet = false;
};

// Buffered CSV writer: one fmt::format_to per row, flushed in large blocks (a 1-hour 1 kHz log is
// 3.6 M rows).
class CsvWriter {
public:
    CsvWriter(const std::string& path, const std::string& header) : path_(path) {
        file_ = std::fopen(path.c_str(), "wb");
        if (!file_) throw InputError(fmt::format("{}: cannot open for writing", path));
        buffer_.append(header.data(), header.data() + header.size());
    }
    // Without close() the run failed half-way (a diverging simulation, a full disk): the file is removed,
    // so that no partial log is left as if it were complete.
    ~CsvWriter() {
        if (!file_) return;
        std::fclose(file_);
        io::remove_partial_output(path_);
    }
    fmt::memory_buffer& buffer() { return buffer_; }
    void row_done() {
        if (buffer_.size() > (1u << 20)) flush();
    }
    void close() {
        flush();
        if (std::fclose(file_) != 0) {
            file_ = nullptr;
            io::remove_partial_output(path_);
            throw InputError(fmt::format("{}: write failed (disk full?)", path_));
        }
        file_ = nullptr;
    }

private:
    void flush() {
        if (std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size()) throw InputError(fmt::format("{}: write failed", path_));
        buffer_.clear();
    }
    std::string path_;
    std::FILE* file_ = nullptr;
    fmt::memory_buffer buffer_;
};

std::string stem(const std::string& path) {
    const auto dot = path.rfind('.');
    const auto slash = path.rfind('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return path;
    return path.substr(0, dot);
}

// The hidden effects of --effect / --effects: the truth is the nominal model plus the effects' columns with
// the injected coefficients; a torque delay acts in the measurement instead, and contacts (external:...) act
// on the physics as a function of time, not as model columns.
struct HiddenEffects {
    std::vector<sim::EffectSpec> effects;
    std::vector<sim::ExternalTorque> contacts;
    std::vector<sim::EffectTerm> terms;
    std::vector<Eigen::VectorXd> coefficients;
    double torque_delay = 0.0;  // s, added to the measurement's
};

HiddenEffects hidden_effects(const SimulateOptions& o, const robot::RobotDescription& robot, const robot::RobotModel& model, const Eigen::VectorXd& x,
                             sim::EffectContext& context) {
    const int n = model.joint_count();
    HiddenEffects h;
    if (!o.effects_file.empty()) h.effects = sim::load_effects_file(o.effects_file, n);
    for (const auto& token : o.effects) {
        if (sim::is_external_torque(token)) {
            h.contacts.push_back(sim::parse_external_torque(token, n));
        } else {
            h.effects.push_back(sim::parse_effect(token, n));
        }
    }
    const bool load_effect = std::any_of(h.effects.begin(), h.effects.end(), [](const sim::EffectSpec& e) { return e.kind == sim::EffectKind::CoulombLoad; });
    if (load_effect) context.load = robot::gravity_load_reference(robot);
    for (const auto& e : h.effects) {
        if (e.kind == sim::EffectKind::TorqueDelay) {
            h.torque_delay += e.value;
            continue;
        }
        const sim::EffectTerm term = sim::term_of(e);
        std::string why_not;
        if (!sim::term_applicable(term, context, &why_not)) throw InputError("--effect " + why_not);
        h.terms.push_back(term);
        h.coefficients.push_back(sim::injected_coefficients(e, model, x));
    }
    return h;
}

// The log must read back: each joint's position and torque in a column of its own, none on the time
// column or on a reference column written after them (identify refuses such a header).
void check_log_columns(const robot::RobotDescription& robot, int n) {
    (void)robot_column_names(robot, "t");
    for (const char* prefix : {"q_ref", "qd_ref"}) {
        for (int k = 1; k <= n; ++k) {
            const std::string name = fmt::format("{}{}", prefix, k);
            for (std::size_t j = 0; j < robot.joints.size(); ++j) {
                for (const std::string* column : {&robot.joints[j].position_column, &robot.joints[j].torque_column}) {
                    if (*column == name) {
                        throw InputError(fmt::format("{}: joint {} ({}) reads column '{}', which is the reference column simulate writes for joint "
                                                     "{}; give it another name",
                                                     robot.source, j + 1, robot.joints[j].name, name, k));
                    }
                }
            }
        }
    }
}

// t, the measured columns, then the reference the controller tracked (what IDIM-IV and DIDIM simulate along);
// with contacts, their truth last (tau_ext1..): what `jacobid monitor` is checked against. Logs without
// contacts keep their columns.
std::string log_header(const robot::RobotDescription& robot, int n, bool external) {
    std::string header = "t";
    for (const auto& j : robot.joints) header += "," + j.position_column;
    for (const auto& j : robot.joints) header += "," + j.torque_column;
    for (const char* prefix : {"q_ref", "qd_ref"}) {
        for (int j = 1; j <= n; ++j) header += fmt::format(",{}{}", prefix, j);
    }
    if (external) {
        for (int j = 1; j <= n; ++j) header += fmt::format(",tau_ext{}", j);
    }
    return header + "\n";
}

std::string states_header(int n, bool external) {
    std::string h = "t";
    for (const char* prefix : {"q", "qd", "qdd", "tau"}) {
        for (int j = 1; j <= n; ++j) h += fmt::format(",{}{}", prefix, j);
    }
    if (external) {
        for (int j = 1; j <= n; ++j) h += fmt::format(",tau_ext{}", j);
    }
    return h + "\n";
}

void append_values(fmt::memory_buffer& b, const Eigen::VectorXd& v, int n, const char* spec) {
    for (int j = 0; j < n; ++j) fmt::format_to(std::back_inserter(b), fmt::runtime(spec), v[j]);
}

nlohmann::json truth_json(const SimulateOptions& o, const robot::RobotDescription& robot, const robot::RobotModel& model, const Eigen::VectorXd& x,
                          const sim::MeasurementSettings& ms, const HiddenEffects& hidden, std::size_t samples) {
    nlohmann::json truth;
    truth["model"] = robot.model;
    truth["robot"] = robot::to_yaml(robot);
    nlohmann::json params = nlohmann::json::object();
    for (int c = 0; c < model.parameter_count(); ++c) params[model.parameter_names()[static_cast<std::size_t>(c)]] = x[c];
    truth["parameters"] = params;
    truth["parameter_order"] = model.parameter_names();
    truth["log"] = o.out;
    truth["states"] = o.states.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.states);
    truth["samples"] = samples;
    truth["simulation"] = {{"duration", o.settings.duration},      {"rate", o.settings.output_rate},
                           {"control_rate", o.settings.control_rate}, {"integration_rate", o.settings.control_rate * o.settings.substeps},
                           {"omega_dyn", o.settings.omega_dyn},     {"damping", o.settings.damping},
                           {"seed", o.settings.seed},               {"move_duration", o.move_duration},
                           {"dwell", o.settings.moves.max_dwell},
                           {"velocity_limit", o.settings.moves.velocity_limit},
                           {"acceleration_limit", o.settings.moves.acceleration_limit},
                           {"trajectory", o.trajectory.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.trajectory)}};
    truth["measurement"] = {{"encoder_counts_per_rev", ms.encoder_counts_per_rev}, {"torque_noise", ms.torque_noise},
                            {"ripple_amplitude", ms.ripple_amplitude},           {"ripple_periods_per_rev", ms.ripple_periods_per_rev},
                            {"position_noise", ms.position_noise},
                            {"seed", ms.seed},
                            {"torque_delay", ms.torque_delay}};
    truth["effects"] = nlohmann::json::array();
    for (const auto& e : hidden.effects) truth["effects"].push_back(sim::to_json(e));
    for (const auto& c : hidden.contacts) truth["effects"].push_back(sim::to_json(c));
    return truth;
}

// The run's reference: the random moves (their limits from --velocity-limit / --acceleration-limit) or a
// given --trajectory table, which is checked by excite or by the user, not changed here.
void apply_reference(SimulateOptions& o, const robot::RobotDescription& robot, int n) {
    std::shared_ptr<const sim::TabulatedTrajectory> reference;
    if (!o.trajectory.empty()) {
        for (const auto& [limit, option] : {std::pair{&o.settings.moves.velocity_limit, "--velocity-limit"}, {&o.settings.moves.acceleration_limit, "--acceleration-limit"}}) {
            if (!limit->empty()) throw InputError(fmt::format("{} shapes the random moves: it cannot be given with --trajectory {}", option, o.trajectory));
        }
        std::vector<std::optional<io::PositionBounds>> limits;
        for (std::size_t j = 0; j < static_cast<std::size_t>(n); ++j) limits.push_back(identify::position_bounds(robot, j));
        reference = std::make_shared<const sim::TabulatedTrajectory>(io::read_csv(o.trajectory), n, limits);
        if (!o.duration_given) o.settings.duration = reference->length();
    }
    o.settings = simulation_settings(o);
    // A log of one row is no log (a 1 ns table used to give one, exit 0).
    if (o.settings.duration * o.settings.output_rate < 1.0) {
        const std::string duration = o.duration_given || o.trajectory.empty() ? fmt::format("--duration {:g} s", o.settings.duration)
                                                                              : fmt::format("--trajectory {} lasts {:g} s (its last t) and", o.trajectory, o.settings.duration);
        throw InputError(fmt::format("{} at --rate {:g} Hz gives a log of one sample; a log needs at least 2 (a duration of at least {:g} s)", duration,
                                     o.settings.output_rate, 1.0 / o.settings.output_rate));
    }
    // A row: the time, then position, torque and two reference columns per joint (10-17 digits each).
    refuse_oversized_simulation(o.settings, 12.0 + 60.0 * n);
    if (reference) {
        o.settings.reference = [reference](double t, sim::ReferenceSample& out) { reference->evaluate(t, out); };
        o.settings.reference_start = reference->start();
    }
}

void run(SimulateOptions o) {
    const robot::RobotDescription robot = o.robot.empty() ? robot::default_planar2r_description() : robot::load_robot_description(o.robot);
    std::vector<NamedPath> inputs = robot_files("--robot", o.robot, robot);
    inputs.insert(inputs.end(), {{"--effects", o.effects_file}, {"--trajectory", o.trajectory}});
    check_outputs({{"--out", o.out}, {"--truth", o.truth.empty() ? stem(o.out) + ".truth.json" : o.truth}, {"--states", o.states}}, inputs);
    const auto model = robot::make_robot_model(robot);
    const int n = model->joint_count();
    // Truth: the model's reference values (Table II for planar2r) unless the description lists parameters.
    const Eigen::VectorXd x = robot::simulated_parameters(robot, *model);

    sim::MeasurementSettings ms = measurement_settings(o, n);
    apply_controller(robot, o);
    apply_reference(o, robot, n);
    sim::EffectContext context{model->model_name(), n, robot.coulomb, robot::joint_coulomb_signs(robot)};
    const HiddenEffects hidden = hidden_effects(o, robot, *model, x, context);
    ms.torque_delay += hidden.torque_delay;
    if (!hidden.contacts.empty()) {
        o.settings.external_torque = [contacts = hidden.contacts, n](double t, Eigen::VectorXd& out) { sim::external_torque_at(contacts, t, n, out); };
    }
    const sim::AugmentedModel truth_model(*model, context, hidden.terms);
    Eigen::VectorXd x_truth(truth_model.parameter_count());
    x_truth.head(model->parameter_count()) = x;
    for (std::size_t t = 0; t < hidden.terms.size(); ++t) {
        x_truth.segment(truth_model.term_column(t), hidden.terms[t].column_count()) = hidden.coefficients[t];
    }
    sim::MeasurementModel measurement(ms);

    check_log_columns(robot, n);
    const bool external = !hidden.contacts.empty();
    CsvWriter log(o.out, log_header(robot, n, external));
    std::unique_ptr<CsvWriter> states;
    if (!o.states.empty()) states = std::make_unique<CsvWriter>(o.states, states_header(n, external));
    const std::size_t total = sim::simulated_sample_count(o.settings);
    const bool progress = !o.quiet && total > 1'000'000;
    std::size_t emitted = 0;
    // t is printed from the sample index so that the time column is exactly uniform in decimal.
    const double period = 1.0 / o.settings.output_rate;
    // Without effects the nominal model itself is integrated, exactly as before effects existed.
    const bool with_terms = !hidden.terms.empty();
    sim::simulate(with_terms ? static_cast<const robot::RobotModel&>(truth_model) : *model, with_terms ? x_truth : x, robot.joints, o.settings, measurement,
                  [&](const sim::SimulatedSample& s) {
                      auto& b = log.buffer();
                      const double t = static_cast<double>(emitted) * period;
                      fmt::format_to(std::back_inserter(b), "{:.6f}", t);
                      append_values(b, s.q_measured, n, ",{:.12g}");
                      append_values(b, s.tau_measured, n, ",{:.10g}");
                      append_values(b, s.q_ref, n, ",{:.15g}");
                      append_values(b, s.qd_ref, n, ",{:.15g}");
                      if (external) append_values(b, s.tau_external, n, ",{:.15g}");
                      b.push_back('\n');
                      log.row_done();
                      if (states) {
                          auto& sb = states->buffer();
                          fmt::format_to(std::back_inserter(sb), "{:.6f}", t);
                          for (const Eigen::VectorXd* v : {&s.q, &s.qd, &s.qdd, &s.tau}) append_values(sb, *v, n, ",{:.15g}");
                          if (external) append_values(sb, s.tau_external, n, ",{:.15g}");
                          sb.push_back('\n');
                          states->row_done();
                      }
                      ++emitted;
                      if (progress && emitted % (total / 10) == 0) fmt::print(stderr, "simulate: {:.0f} %\n", 100.0 * static_cast<double>(emitted) / static_cast<double>(total));
                  });
    log.close();
    if (states) states->close();
    write_output(o.truth.empty() ? stem(o.out) + ".truth.json" : o.truth, truth_json(o, robot, *model, x, ms, hidden, emitted).dump(2) + "\n");
}

}  // namespace

void add_simulate_command(CLI::App& app) {
    auto o = std::make_shared<SimulateOptions>();
    CLI::App* cmd = app.add_subcommand(
        "simulate",
        "simulate a PD-controlled robot on random quintic point-to-point moves; write the measured log (CSV t,q..,tau.., then the "
        "reference q_ref..,qd_ref..) "
        "and the truth (JSON parameters, optional CSV of noise-free states)");
    cmd->add_option("--robot", o->robot, "robot description (YAML); default: planar2r, L1 0.5 m, smoothed Coulomb friction alpha 100 (a description whose alpha is auto, the default, is simulated with 100 s/rad)")->check(file_path());
    cmd->add_option("--out,-o", o->out, "output log (CSV)")->required()->check(file_path());
    cmd->add_option("--truth", o->truth, "truth file (JSON: parameters, settings); default <out without extension>.truth.json")->check(file_path());
    cmd->add_option("--states", o->states, "also write the noise-free states t,q,qd,qdd,tau to this CSV")->check(file_path());
    add_simulation_options(cmd, *o);
    cmd->add_option("--effect", o->effects,
                    "inject an effect the nominal model lacks (repeatable): NAME:key=value,... e.g. "
                    "coulomb_offset:joint=1,value=0.3 | coulomb_asymmetry:joint=1,value=0.1 | "
                    "stribeck:joint=1,value=0.3,velocity=0.1 | viscous_nonlinear:joint=2,value=0.05 | "
                    "gravity:tilt=3,direction=0,mx1=1.5 | cogging:joint=2,amplitude=0.2,order=6,phase=0 | "
                    "rotor_inertia:joint=2,value=0.1 | torque_delay:value=0.003 | "
                    "external:joint=2,start=1.5,duration=0.2,value=10[,shape=pulse|sine|ramp] (a contact: a torque on the joint, "
                    "its truth logged as tau_ext1.. columns; docs/monitor.md) (joints 1-based, SI units, "
                    "angles in degrees; see docs/diagnose.md)")
        ->take_all();
    cmd->add_option("--effects", o->effects_file, "YAML file of effects to inject: effects: [{name: cogging, joint: 2, amplitude: 0.2, order: 6}, ...]")->check(file_path());
    cmd->add_option("--trajectory", o->trajectory,
                    "follow this reference instead of random moves: CSV t,q1..,qd1..,qdd1.. (e.g. from jacobid excite), repeated after its "
                    "last row; --duration defaults to its length")->check(file_path());
    cmd->add_flag("--quiet", o->quiet, "no progress messages on stderr");
    cmd->callback([o, cmd] {
        o->duration_given = cmd->count("--duration") > 0;
        run(*o);
    });
}

}  // namespace jacobid::cli
