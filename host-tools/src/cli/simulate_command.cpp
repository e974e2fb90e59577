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
#include "identify/log_columns.hpp"
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
    std::shared_ptr<const sim::TabulatedTrajectory> reference;
    if (!o.trajectory.empty()) {
        // The limits shape the random moves; a given table is checked by excite or by the user, not changed here.
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

    // Hidden effects: the truth is the nominal model plus the effects' columns with the injected
    // coefficients; a torque delay acts in the measurement instead.
    std::vector<sim::EffectSpec> effects;
    if (!o.effects_file.empty()) effects = sim::load_effects_file(o.effects_file, n);
    // Contacts (external:...) act on the physics as a function of time, not as model columns.
    std::vector<sim::ExternalTorque> contacts;
    for (const auto& token : o.effects) {
        if (sim::is_external_torque(token)) {
            contacts.push_back(sim::parse_external_torque(token, n));
        } else {
            effects.push_back(sim::parse_effect(token, n));
        }
    }
    if (!contacts.empty()) {
        o.settings.external_torque = [contacts, n](double t, Eigen::VectorXd& out) { sim::external_torque_at(contacts, t, n, out); };
    }
    std::vector<sim::EffectTerm> terms;
    std::vector<Eigen::VectorXd> coefficients;
    sim::EffectContext context{model->model_name(), n, robot.coulomb, robot::joint_coulomb_signs(robot)};
    const bool load_effect = std::any_of(effects.begin(), effects.end(), [](const sim::EffectSpec& e) { return e.kind == sim::EffectKind::CoulombLoad; });
    if (load_effect) context.load = robot::gravity_load_reference(robot);
    for (const auto& e : effects) {
        if (e.kind == sim::EffectKind::TorqueDelay) {
            ms.torque_delay += e.value;
            continue;
        }
        const sim::EffectTerm term = sim::term_of(e);
        std::string why_not;
        if (!sim::term_applicable(term, context, &why_not)) throw InputError("--effect " + why_not);
        terms.push_back(term);
        coefficients.push_back(sim::injected_coefficients(e, *model, x));
    }
    const sim::AugmentedModel truth_model(*model, context, terms);
    Eigen::VectorXd x_truth(truth_model.parameter_count());
    x_truth.head(model->parameter_count()) = x;
    for (std::size_t t = 0; t < terms.size(); ++t) {
        x_truth.segment(truth_model.term_column(t), terms[t].column_count()) = coefficients[t];
    }
    sim::MeasurementModel measurement(ms);

    // The log must read back: each joint's position and torque in a column of its own, none on the time
    // column or on a reference column written after them (identify refuses such a header).
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
    std::string header = "t";
    for (const auto& j : robot.joints) header += "," + j.position_column;
    for (const auto& j : robot.joints) header += "," + j.torque_column;
    // The reference the controller tracked, after the measured columns (what IDIM-IV and DIDIM simulate along).
    for (const char* prefix : {"q_ref", "qd_ref"}) {
        for (int j = 1; j <= n; ++j) header += fmt::format(",{}{}", prefix, j);
    }
    // With contacts, their truth last (tau_ext1..): what `jacobid monitor` is checked against; logs without
    // contacts keep their columns.
    const bool external = !contacts.empty();
    if (external) {
        for (int j = 1; j <= n; ++j) header += fmt::format(",tau_ext{}", j);
    }
    header += "\n";
    CsvWriter log(o.out, header);
    std::unique_ptr<CsvWriter> states;
    if (!o.states.empty()) {
        std::string h = "t";
        for (const char* prefix : {"q", "qd", "qdd", "tau"}) {
            for (int j = 1; j <= n; ++j) h += fmt::format(",{}{}", prefix, j);
        }
        if (external) {
            for (int j = 1; j <= n; ++j) h += fmt::format(",tau_ext{}", j);
        }
        states = std::make_unique<CsvWriter>(o.states, h + "\n");
    }
    const std::size_t total = sim::simulated_sample_count(o.settings);
    const bool progress = !o.quiet && total > 1'000'000;
    std::size_t emitted = 0;
    // t is printed from the sample index so that the time column is exactly uniform in decimal.
    const double period = 1.0 / o.settings.output_rate;
    // Without effects the nominal model itself is integrated, exactly as before effects existed.
    const bool hidden = !terms.empty();
    sim::simulate(hidden ? static_cast<const robot::RobotModel&>(truth_model) : *model, hidden ? x_truth : x, robot.joints, o.settings, measurement, [&](const sim::SimulatedSample& s) {
        auto& b = log.buffer();
        const double t = static_cast<double>(emitted) * period;
        fmt::format_to(std::back_inserter(b), "{:.6f}", t);
        for (int j = 0; j < n; ++j) fmt::format_to(std::back_inserter(b), ",{:.12g}", s.q_measured[j]);
        for (int j = 0; j < n; ++j) fmt::format_to(std::back_inserter(b), ",{:.10g}", s.tau_measured[j]);
        for (const Eigen::VectorXd* v : {&s.q_ref, &s.qd_ref}) {
            for (int j = 0; j < n; ++j) fmt::format_to(std::back_inserter(b), ",{:.15g}", (*v)[j]);
        }
        if (external) {
            for (int j = 0; j < n; ++j) fmt::format_to(std::back_inserter(b), ",{:.15g}", s.tau_external[j]);
        }
        b.push_back('\n');
        log.row_done();
        if (states) {
            auto& sb = states->buffer();
            fmt::format_to(std::back_inserter(sb), "{:.6f}", t);
            for (const Eigen::VectorXd* v : {&s.q, &s.qd, &s.qdd, &s.tau}) {
                for (int j = 0; j < n; ++j) fmt::format_to(std::back_inserter(sb), ",{:.15g}", (*v)[j]);
            }
            if (external) {
                for (int j = 0; j < n; ++j) fmt::format_to(std::back_inserter(sb), ",{:.15g}", s.tau_external[j]);
            }
            sb.push_back('\n');
            states->row_done();
        }
        ++emitted;
        if (progress && emitted % (total / 10) == 0) fmt::print(stderr, "simulate: {:.0f} %\n", 100.0 * static_cast<double>(emitted) / static_cast<double>(total));
    });
    log.close();
    if (states) states->close();

    nlohmann::json truth;
    truth["model"] = robot.model;
    truth["robot"] = robot::to_yaml(robot);
    nlohmann::json params = nlohmann::json::object();
    for (int c = 0; c < model->parameter_count(); ++c) params[model->parameter_names()[static_cast<std::size_t>(c)]] = x[c];
    truth["parameters"] = params;
    truth["parameter_order"] = model->parameter_names();
    truth["log"] = o.out;
    truth["states"] = o.states.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.states);
    truth["samples"] = emitted;
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
    for (const auto& e : effects) truth["effects"].push_back(sim::to_json(e));
    for (const auto& c : contacts) truth["effects"].push_back(sim::to_json(c));
    write_output(o.truth.empty() ? stem(o.out) + ".truth.json" : o.truth, truth.dump(2) + "\n");
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
