// SPDX-License-Identifier: MIT
// jacobid::host: the library calls of `jacobid simulate`, `identify` and `diagnose` on one continuous log, with
// their options given as keywords and parsed by the command line's own definitions (options/*_options), and their
// results converted from the host library's JSON producers, so the names and values are the CLI's. Arguments are
// plain Python objects checked by the module's one layer (python_values, numpy_views, cli_arguments) before
// anything is read or computed.
#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <memory>

#include "bindings.hpp"
#include "host_values.hpp"
#include "options/diagnose_options.hpp"
#include "job/identify_job.hpp"
#include "options/drive_gains_options.hpp"
#include "options/identify_options.hpp"
#include "options/log_format_options.hpp"
#include "options/output_file.hpp"
#include "options/simulation_options.hpp"
#include "cli_arguments.hpp"
#include "core/errors.hpp"
#include "diagnose/diagnose_log.hpp"
#include "diagnose/diagnosis_report.hpp"
#include "identify/solve/least_squares.hpp"
#include "identify/plan/log_columns.hpp"
#include "identify/report/report.hpp"
#include "identify/validation/validate_log.hpp"
#include "io/csv_table.hpp"
#include "io/time_axis.hpp"
#include "json_to_python.hpp"
#include "numpy_views.hpp"
#include "python_values.hpp"
#include "truth_argument.hpp"
#include "robot/base_parameter_report.hpp"
#include "robot/robot_description.hpp"
#include "robot/simulated_parameters.hpp"
#include "sim/measurement.hpp"
#include "sim/simulator.hpp"

namespace py = pybind11;

namespace jacobid::python {

Robot load_robot(const py::object& path, const py::args& extra, const py::kwargs& keywords) {
    refuse_extra_positional("load_robot", extra, {"path"});
    refuse_unknown_keywords("load_robot", keywords, {"path"});
    Robot r;
    if (path.is_none()) {
        r.description = robot::default_planar2r_description();
    } else {
        const std::string file = path_text(path, "path");
        options::check_outputs({}, {{"--robot", file}});
        r.description = robot::load_robot_description(file);
    }
    r.model = robot::make_robot_model(r.description);
    return r;
}

py::object robot_path(const Robot& r) {
    if (r.description.source == robot::default_planar2r_description().source) return py::none();
    return py::module_::import("os").attr("path").attr("abspath")(text_of(r.description.source));
}

// The `robot` argument of simulate, identify and diagnose: a Robot, or what load_robot reads (a path; None: the planar 2R).
Robot robot_of(const py::handle& value) {
    if (py::isinstance<Robot>(value)) return value.cast<const Robot&>();
    if (value.is_none() || is_path(value)) return load_robot(py::reinterpret_borrow<py::object>(value), py::args(), py::kwargs());
    throw InputError(fmt::format("robot: expected a Robot or the path of a robot description, got {}", type_name(value)));
}

namespace {

std::vector<std::string> joint_field(const Robot& r, std::string robot::JointDescription::*field) {
    std::vector<std::string> names;
    for (const auto& j : r.description.joints) names.push_back(j.*field);
    return names;
}

// --- simulate ---------------------------------------------------------------------------------------------

py::dict simulate(const py::object& robot_value, const py::args& extra, const py::kwargs& keywords) {
    refuse_extra_positional("simulate", extra, {"robot"});
    options::SimulationOptions o;
    CLI::App app("", "simulate");
    options::add_simulation_options(&app, o);
    parse_keywords(app, keywords, {"robot"});
    const Robot r = robot_of(robot_value);
    const robot::RobotModel& model = *r.model;
    const int n = model.joint_count();
    const Eigen::VectorXd x = robot::simulated_parameters(r.description, model);
    // In the order of `jacobid simulate`: the sensors, the description's controller, then the checked settings.
    const sim::MeasurementSettings ms = options::measurement_settings(o, n);
    options::apply_controller(r.description, o);
    o.settings = options::simulation_settings(o);
    options::refuse_oversized_simulation(o.settings, 8.0 * (1.0 + 6.0 * n));  // t + q, tau, q_ref, qd_ref per joint, doubles
    sim::MeasurementModel measurement(ms);
    const std::size_t total = sim::simulated_sample_count(o.settings);
    const auto joints = static_cast<std::size_t>(n);
    py::array_t<double> t(total);
    py::array_t<double> q = new_matrix(total, joints), tau = new_matrix(total, joints), q_ref = new_matrix(total, joints),
                        qd_ref = new_matrix(total, joints);
    double* columns[] = {q.mutable_data(), tau.mutable_data(), q_ref.mutable_data(), qd_ref.mutable_data()};
    double* time = t.mutable_data();
    std::size_t emitted = 0;
    const double period = 1.0 / o.settings.output_rate;
    {
        py::gil_scoped_release unlocked;
        sim::simulate(model, x, r.description.joints, o.settings, measurement, [&](const sim::SimulatedSample& s) {
            if (emitted >= total) return;
            // The time from the sample index, as the CLI writes it (an exactly uniform axis).
            time[emitted] = static_cast<double>(emitted) * period;
            const Eigen::VectorXd* rows[] = {&s.q_measured, &s.tau_measured, &s.q_ref, &s.qd_ref};
            for (int k = 0; k < 4; ++k) {
                for (std::size_t j = 0; j < joints; ++j) columns[k][emitted * joints + j] = (*rows[k])[static_cast<Eigen::Index>(j)];
            }
            ++emitted;
        });
    }
    py::dict d;
    d["t"] = t;
    d["q"] = q;
    d["tau"] = tau;
    d["q_ref"] = q_ref;
    d["qd_ref"] = qd_ref;
    // The truth, named as in `jacobid simulate --truth`'s JSON.
    py::dict parameters;
    for (int c = 0; c < model.parameter_count(); ++c) parameters[py::str(model.parameter_names()[static_cast<std::size_t>(c)])] = x[c];
    d["model"] = r.description.model;
    d["parameters"] = parameters;
    d["parameter_order"] = model.parameter_names();
    d["samples"] = emitted;
    return d;
}

// --- logs: a file read as the CLI reads --in, or numpy arrays t, q, tau -------------------------------------

struct LogKeywords {
    options::LogFormatOptions log_format;
    std::string time_column = "t";
    double time_tolerance = io::kDefaultTimeTolerance;
    bool quiet = false;
};

void add_log_keywords(CLI::App& app, LogKeywords& o) {
    options::add_log_format_options(&app, o.log_format);
    options::add_time_tolerance_option(&app, o.time_tolerance);
    app.add_option("--time-column", o.time_column, "name of the time column (s)");
    app.add_flag("--quiet", o.quiet, "no progress messages on stderr");
}

// The table of a log given as t, q, tau: q and tau samples x joints, in the robot's column names.
io::CsvTable table_of_arrays(const Robot& r, const py::handle& t_value, const py::handle& q_value, const py::handle& tau_value,
                             const std::string& time_column, const std::string& what) {
    const DoubleArray t_array = checked_array(t_value, what + " t", Layout::Samples), q_array = checked_array(q_value, what + " q", Layout::SamplesByJoints),
                      tau_array = checked_array(tau_value, what + " tau", Layout::SamplesByJoints);
    const Span<const double> t = samples_of(t_array);
    const Matrix q = matrix_of(q_array), tau = matrix_of(tau_array);
    const std::size_t joints = r.description.joints.size();
    for (const auto& [name, m] : {std::pair<const char*, const Matrix&>{"q", q}, {"tau", tau}}) {
        if (m.rows != t.size() || m.columns != joints) {
            throw InputError(fmt::format("{} {}: {} x {} samples, expected {} x {} (t's samples x the robot's joints)", what, name, m.rows,
                                         m.columns, t.size(), joints));
        }
    }
    std::vector<std::string> header{time_column};
    for (const auto& j : r.description.joints) header.push_back(j.position_column);
    for (const auto& j : r.description.joints) header.push_back(j.torque_column);
    // Named "--in arrays" with rows numbered from 0: where a shared check names a line ("--in arrays:5: column
    // 'q2': ..."), the number is the sample's index in t, q and tau.
    io::CsvTable table(what + " arrays", header);
    table.set_first_line(0);
    // `index` names sample i in messages ("[i]", "[i, j]").
    auto fill = [&](std::size_t column, const std::string& name, auto value_at, auto index) {
        std::vector<double>& c = table.mutable_column(column);
        c.resize(t.size());
        for (std::size_t i = 0; i < t.size(); ++i) {
            c[i] = value_at(i);
            // What the CSV reader refuses, refused here too (never identified from); non-finite values are refused by checked_array.
            if (io::beyond_log_range(c[i])) throw InputError(fmt::format("{} {}{}: {} {}", what, name, index(i), c[i], io::kBeyondLogRange));
        }
    };
    fill(0, "t", [&](std::size_t i) { return t[i]; }, [](std::size_t i) { return fmt::format("[{}]", i); });
    for (std::size_t j = 0; j < joints; ++j) {
        const auto at_joint = [j](std::size_t i) { return fmt::format("[{}, {}]", i, j); };
        fill(1 + j, "q", [&](std::size_t i) { return q.at(i, j); }, at_joint);
        fill(1 + joints + j, "tau", [&](std::size_t i) { return tau.at(i, j); }, at_joint);
    }
    return table;
}

std::string source_name(const py::handle& source, const std::string& option) { return is_path(source) ? path_text(source, option) : option; }

// A log: a path (read as --in reads it), a tuple or list (t, q, tau), or simulate()'s result (a dict with t, q,
// tau). `option` names the source in messages ("--in", "--validate"), as the command line does.
io::CsvTable read_log(const Robot& r, const py::handle& source, const LogKeywords& o, const std::string& option, double period = 0.0) {
    if (py::isinstance<py::dict>(source)) {
        const py::dict run = py::reinterpret_borrow<py::dict>(source);
        for (const char* key : {"t", "q", "tau"}) {
            if (!run.contains(key)) throw InputError(fmt::format("{}: a dict without '{}'; expected simulate()'s result (keys t, q, tau)", option, key));
        }
        return table_of_arrays(r, run["t"], run["q"], run["tau"], o.time_column, option);
    }
    if (py::isinstance<py::tuple>(source) || py::isinstance<py::list>(source)) {
        const py::sequence arrays = py::reinterpret_borrow<py::sequence>(source);
        if (arrays.size() != 3) throw InputError(fmt::format("{}: expected a path or a tuple (t, q, tau), got {} items", option, arrays.size()));
        return table_of_arrays(r, arrays[0], arrays[1], arrays[2], o.time_column, option);
    }
    if (!is_path(source)) {
        throw InputError(fmt::format("{}: expected a path, a tuple (t, q, tau) or simulate()'s result, got {}", option, type_name(source)));
    }
    const std::string path = path_text(source, option);
    options::check_outputs({}, {{option, path}, {"--log-format", o.log_format.file}});
    return options::read_log_table(path, o.log_format, options::robot_column_names(r.description, o.time_column), o.quiet, period);
}

}  // namespace

// --- identify ----------------------------------------------------------------------------------------------

// A log of identify (job/identify_inputs.hpp): a path, read by the job as --in reads it (--log-format, --on-gap
// split, --can-config, in pieces when long), or arrays made into a table here. `option` names it in messages.
job::LogSource log_source(const Robot& r, const py::handle& source, const std::string& time_column, const std::string& option) {
    if (is_path(source)) return {path_text(source, option), std::nullopt};
    LogKeywords arrays;
    arrays.time_column = time_column;
    return {option, read_log(r, source, arrays, option)};
}

// identify's `log`: one log, or a list of logs identified together (--in a --in b): a list whose items are logs
// themselves (paths, (t, q, tau) tuples, simulate()'s dicts), where a list of three arrays is one (t, q, tau) log.
bool several_logs(const py::handle& value) {
    if (!py::isinstance<py::list>(value) && !py::isinstance<py::tuple>(value)) return false;
    const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
    if (items.size() == 0) return true;
    const py::handle first = items[0];
    if (is_path(first) || py::isinstance<py::dict>(first)) return true;
    // A (t, q, tau) log as the first of several: itself a sequence whose first item (t) is a sequence; the t of one
    // log is a sequence of numbers.
    if (!py::isinstance<py::tuple>(first) && !py::isinstance<py::list>(first)) return false;
    const py::sequence log = py::reinterpret_borrow<py::sequence>(first);
    return log.size() == 3 && py::hasattr(log[0], "__len__");
}

std::vector<job::LogSource> log_sources(const Robot& r, const py::handle& source, const std::string& time_column) {
    std::vector<job::LogSource> logs;
    if (several_logs(source)) {
        const py::sequence items = py::reinterpret_borrow<py::sequence>(source);
        if (items.size() == 0) throw InputError("log: an empty list; expected a log or a list of logs");
        for (std::size_t k = 0; k < items.size(); ++k) logs.push_back(log_source(r, items[k], time_column, fmt::format("--in[{}]", k)));
    } else {
        logs.push_back(log_source(r, source, time_column, "--in"));
    }
    return logs;
}

namespace {

py::dict identify(const py::object& robot_value, const py::object& source, const py::object& validation, const py::object& truth,
                  const py::args& extra, const py::kwargs& keywords) {
    refuse_extra_positional("identify", extra, {"robot", "log", "validate", "truth"});
    options::IdentifyOptions o;
    CLI::App app("", "identify");
    options::add_identify_options(&app, o);
    parse_keywords(app, keywords, {"robot", "log", "validate", "truth"});
    options::finish_identify_options(o);
    const Robot r = robot_of(robot_value);
    const robot::RobotModel& model = *r.model;
    o.robot = r.description.source;
    // Before the logs are read: a wrong truth is refused at once.
    const std::map<std::string, double> truth_by_name = truth.is_none() ? std::map<std::string, double>{} : truth_values(truth, model.parameter_names());
    std::vector<job::LogSource> logs = log_sources(r, source, o.time_column);
    for (const job::LogSource& l : logs) o.inputs.push_back(l.name);
    std::optional<job::LogSource> validation_log;
    if (!validation.is_none()) {
        validation_log = log_source(r, validation, o.time_column, "--validate");
        o.validate = validation_log->name;
    }
    job::check_identify_files(o, r.description, {});
    if (o.drive_gains.enabled) {
        if (logs.size() != 1 || logs.front().table) throw InputError("drive_gains: give the unloaded run as log (one path) and the loaded one as loaded");
        const std::vector<std::pair<std::string, bool>> given = {{"validate", !validation.is_none()}, {"report", !o.report.empty()},
                                                                 {"truth", !truth.is_none()}, {"essential", o.essential_flag},
                                                                 {"physical", o.physical || o.semi_physical}, {"can_config", !o.can_config.empty()},
                                                                 {"velocity", !o.velocity.empty()}, {"export_urdf / export_robot", o.model_export.any()},
                                                                 {"period", !o.period.empty()}};
        std::string text;
        {
            py::gil_scoped_release unlocked;
            job::resolve_threads(o);
            text = options::run_drive_gains(r.description, model, o.drive_gains, o, o.method,
                                            {o.first_input(), "json", o.time_column, o.time_tolerance, o.quiet, &o.log_format, given});
        }
        return to_python(nlohmann::json::parse(text));
    }
    nlohmann::json j;
    {
        py::gil_scoped_release unlocked;
        j = job::to_json(job::run_identify(r.description, model, o, std::move(logs), std::move(validation_log), truth_by_name));
    }
    return to_python(j);
}

// --- diagnose -----------------------------------------------------------------------------------------------

py::dict diagnose(const py::object& robot_value, const py::object& source, const py::object& validation, const py::args& extra,
                  const py::kwargs& keywords) {
    refuse_extra_positional("diagnose", extra, {"robot", "log", "validate"});
    diagnose::DiagnoseSettings settings;
    bool no_delay = false;
    LogKeywords o;
    CLI::App app("", "diagnose");
    options::add_diagnose_search_options(&app, settings, no_delay);
    add_log_keywords(app, o);
    parse_keywords(app, keywords, {"robot", "log", "validate"});
    const Robot r = robot_of(robot_value);
    options::refuse_split(o.log_format, "diagnose");
    const robot::RobotModel& model = *r.model;
    const io::CsvTable table = read_log(r, source, o, "--in");
    const identify::LogColumns log = identify::log_columns(table, r.description, o.time_column, o.time_tolerance);
    options::refuse_oversized_search(settings, log, model);
    std::unique_ptr<io::CsvTable> validation_table;
    identify::LogColumns validation_log;
    if (!validation.is_none()) {
        validation_table = std::make_unique<io::CsvTable>(read_log(r, validation, o, "--validate", log.sample_period));
        validation_log = identify::log_columns(*validation_table, r.description, o.time_column, o.time_tolerance);
        if (std::abs(validation_log.sample_period - log.sample_period) > 1e-9 * log.sample_period) {
            throw InputError(fmt::format("--validate {}: sample period {} s differs from {} s of --in", source_name(validation, "--validate"),
                                         validation_log.sample_period, log.sample_period));
        }
    }
    settings.selection.search_delay = !no_delay;
    settings.catalogue.torque_delay = !no_delay;
    nlohmann::json j;
    {
        py::gil_scoped_release unlocked;
        const auto progress = [&](const std::string& line) {
            if (!o.quiet) fmt::print(stderr, "diagnose: {}\n", line);
        };
        j = diagnose::to_json(diagnose::diagnose_log(r.description, model, log, validation.is_none() ? nullptr : &validation_log, settings, progress));
    }
    return to_python(j);
}

}  // namespace

void bind_host(py::module_& m) {
    py::class_<Robot>(m, "Robot", "A robot description (YAML: planar2r, an MDH table or a URDF file; docs/robots.md) and its model.")
        .def_property_readonly("model", [](const Robot& r) { return r.model->model_name(); }, "the model's name (planar2r, mdh, urdf)")
        .def(py::init([](const py::object& path) { return load_robot(path, py::args(), py::kwargs()); }), py::arg("path") = py::none(),
             "Robot(path=None): load_robot(path)")
        .def_property_readonly("source", [](const Robot& r) { return text_of(r.description.source); }, "the description's file")
        .def_property_readonly("joint_names", [](const Robot& r) { return joint_field(r, &robot::JointDescription::name); })
        .def_property_readonly("position_columns", [](const Robot& r) { return joint_field(r, &robot::JointDescription::position_column); },
                               "the log's position column of each joint")
        .def_property_readonly("torque_columns", [](const Robot& r) { return joint_field(r, &robot::JointDescription::torque_column); },
                               "the log's torque column of each joint")
        .def_property_readonly("parameter_names", [](const Robot& r) { return r.model->parameter_names(); }, "the base parameters, in order")
        .def("base_parameters",
             [](const Robot& r, const py::args& extra, const py::kwargs& keywords) {
                 refuse_extra_positional("base_parameters", extra, {});
                 refuse_unknown_keywords("base_parameters", keywords, {});
                 return to_python(robot::base_parameter_json(r.description, *r.model));
             },
             "The base parameters with their regrouping relations and true values, as `jacobid identify --print-base --format json`.")
        // Pickled as the description's file (absolute), read again where it is unpickled: a fleet's workers read it
        // from shared storage as they read the logs (docs/fleet.md).
        .def(py::pickle([](const Robot& r) { return py::make_tuple(robot_path(r)); },
                        [](const py::tuple& state) { return load_robot(state[0], py::args(), py::kwargs()); }))
        .def("__repr__", [](const Robot& r) { return text_of(fmt::format("Robot(model={}, joints={}, source={})", r.model->model_name(), r.model->joint_count(), r.description.source)); });
    // Every argument defaults to None, so that a missing one reaches the checks instead of pybind11's
    // "incompatible function arguments" (None: the planar 2R for a robot, "expected a path ..." for a log).
    const py::object none = py::none();
    m.def("load_robot", &load_robot, py::arg("path") = none,
          "load_robot(path=None) -> Robot\n\nReads a robot description as `--robot` does; None: the paper's planar 2R (Table II).");
    m.def("simulate", &simulate, py::arg("robot") = none,
          "simulate(robot, *, duration=..., rate=..., seed=..., torque_noise=..., ...) -> dict\n\n"
          "A closed-loop simulated log as `jacobid simulate` writes it (the keywords are its simulation options: duration, "
          "rate, control_rate, substeps, omega_dyn, damping, seed, move_duration, dwell, encoder_counts, position_noise, "
          "torque_noise, ripple, ripple_periods, noise_seed; a sequence for per-joint values). Returns t (s), q, tau, q_ref, "
          "qd_ref (samples x joints numpy arrays) and the truth as simulate's --truth JSON names it: model, parameters, "
          "parameter_order, samples.");
    m.def("_identify", &identify, py::arg("robot") = none, py::arg("log") = none, py::arg("validate") = none, py::arg("truth") = none);
    m.def("_diagnose", &diagnose, py::arg("robot") = none, py::arg("log") = none, py::arg("validate") = none);
}

}  // namespace jacobid::python
