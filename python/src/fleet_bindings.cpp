// SPDX-License-Identifier: MIT
// jacobid.plan / factor / merge: `identify --in a --in b ...` as a map-reduce (docs/fleet.md). The pieces are the
// identify job's own (job/identify_plan.hpp: plan_method, factor_log, solve_plan; identify::merge_segments), so a
// merge of factors gives the command's JSON. Plans and factors pickle (fleet_codec.hpp), so that Dask
// (jacobid.fleet) can send them between processes and hosts.
#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <pybind11/stl.h>

#include <chrono>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <set>

#include "bindings.hpp"
#include "cli_arguments.hpp"
#include "core/errors.hpp"
#include "fleet_codec.hpp"
#include "host_values.hpp"
#include "job/identify_job.hpp"
#include "job/identify_plan.hpp"
#include "json_to_python.hpp"
#include "options/fit_options.hpp"
#include "options/identify_options.hpp"
#include "python_values.hpp"

namespace py = pybind11;

namespace jacobid::python {
namespace {

// identify's options for a plan: parsed as identify parses them; what needs one continuous log or the whole run in
// one process refused. Threads resolved (0: one per core).
options::IdentifyOptions plan_options(const py::dict& keywords) {
    options::IdentifyOptions o;
    CLI::App app("", "identify");
    options::add_identify_options(&app, o);
    parse_keywords(app, keywords, {"robot", "log"});
    options::finish_identify_options(o);
    const std::vector<std::pair<const char*, bool>> refused = {
        {"period", !o.period.empty()},   {"piece_rows", o.piece_rows > 0},        {"drive_gains", o.drive_gains.enabled},
        {"report", !o.report.empty()},   {"export_urdf / export_robot", o.model_export.any()}};
    for (const auto& [name, given] : refused) {
        if (given) throw InputError(fmt::format("{}: not available in plan (use identify); a plan's logs are factored one by one", name));
    }
    for (const identify::Method m : options::methods_of(o.method)) {
        const identify::Estimator e = options::identify_settings(o, m).estimator.estimator;
        if (identify::is_iterated(e)) {
            throw InputError(fmt::format("estimator {}: the estimator simulates one continuous log; a plan's logs are merged (use wls or ols)",
                                         identify::to_string(e)));
        }
    }
    job::resolve_threads(o);
    return o;
}

// The method's pipeline settings and solver options from the options, as run_identify makes them.
identify::IdentifySettings method_settings(const options::IdentifyOptions& o, identify::Method m) {
    identify::IdentifySettings s = options::identify_settings(o, m);
    s.pipeline = options::method_pipeline(o.pipeline, m, o.velocity, o.method);
    return s;
}

struct Plan {
    Robot robot;
    py::dict keywords;  // as given: what the plan is pickled with (the options are parsed again where it is unpickled)
    options::IdentifyOptions o;
    std::vector<job::MethodPlan> methods;  // one per method of o.method
    std::string bytes;                     // encode_plan(methods): the plan's identity, and what it travels as
    std::string reference;                 // the log it was resolved on
    double sample_period = 0.0;            // s, of that log: every log of the plan must share it
    double grid_period = 0.0;              // s, a raw log's grid (log_format): every raw log is resampled onto it

    // `methods` from their bytes, each with its full settings (identify::imposed_settings, as plan_segments imposes them).
    std::vector<job::MethodPlan> decoded() const {
        std::vector<job::MethodPlan> plans = decode_plan(bytes, robot.description);
        for (job::MethodPlan& p : plans) {
            std::vector<double> ratios = std::move(p.segments.fixed.coulomb_velocity_ratios);
            p.segments.fixed = identify::imposed_settings(method_settings(o, p.method).pipeline, p.segments.info);
            p.segments.fixed.coulomb_velocity_ratios = std::move(ratios);
        }
        return plans;
    }
};

struct Factor {
    std::shared_ptr<const Plan> plan;
    FactorData data;
};

std::shared_ptr<Plan> make_plan(const py::object& robot_value, const py::object& source, const py::args& extra, const py::kwargs& keywords) {
    refuse_extra_positional("plan", extra, {"robot", "log"});
    auto p = std::make_shared<Plan>();
    p->keywords = py::dict(keywords);
    p->o = plan_options(keywords);
    p->robot = robot_of(robot_value);
    const robot::RobotDescription& robot = p->robot.description;
    std::vector<job::LogSource> logs = log_sources(p->robot, source, p->o.time_column);
    for (const job::LogSource& l : logs) p->o.inputs.push_back(l.name);
    p->o.robot = robot.source;
    job::check_identify_files(p->o, robot, {});
    {
        py::gil_scoped_release unlocked;
        const job::InputLogs in = job::read_inputs(std::move(logs), robot, p->o);
        for (const identify::Method m : options::methods_of(p->o.method)) {
            const identify::IdentifySettings s = method_settings(p->o, m);
            p->methods.push_back(job::plan_method(in.columns, {"--in", "log"}, robot, *p->robot.model, s.pipeline, s.solve, options::given_torque_delay(p->o)));
        }
        const std::size_t reference = p->methods.front().segments.reference;
        p->reference = in.names[reference];
        p->sample_period = in.columns[reference].sample_period;
        p->grid_period = in.read.front().grid_period;
        p->bytes = encode_plan(p->methods);
    }
    return p;
}

py::tuple plan_state(const Plan& p) {
    return py::make_tuple(robot_path(p.robot), p.keywords, py::bytes(p.bytes), p.reference, p.sample_period, p.grid_period);
}

std::shared_ptr<Plan> plan_of_state(const py::tuple& state) {
    if (state.size() != 6) throw InputError("plan: not a pickled jacobid plan");
    auto p = std::make_shared<Plan>();
    p->robot = robot_of(state[0]);
    p->keywords = state[1].cast<py::dict>();
    p->o = plan_options(p->keywords);
    p->o.robot = p->robot.description.source;
    p->bytes = state[2].cast<std::string>();
    p->methods = p->decoded();
    p->reference = state[3].cast<std::string>();
    p->sample_period = state[4].cast<double>();
    p->grid_period = state[5].cast<double>();
    return p;
}

// Plans unpickled in this process, by their pickled state and the text of their robot description: a Dask worker
// receives the plan with every task and with every factor moved to it, and making it again (the description's
// YAML and model, the options, the smoothed models) took 2-6 ms each time (docs/fleet.md). A plan does not change
// once made; one is kept while something holds it.
std::shared_ptr<Plan> cached_plan_of_state(const py::tuple& state) {
    static std::map<std::string, std::weak_ptr<Plan>> cache;  // used with the GIL held
    std::string key = py::module_::import("pickle").attr("dumps")(state).cast<std::string>();
    if (state.size() == 6 && !state[0].is_none()) {
        std::ifstream in(path_text(state[0], "robot"), std::ios::binary);
        if (!in) return plan_of_state(state);  // unreadable: plan_of_state says why
        key += '\0' + std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    if (const std::shared_ptr<Plan> known = cache[key].lock()) return known;
    std::shared_ptr<Plan> p = plan_of_state(state);
    for (auto it = cache.begin(); it != cache.end();) it = it->second.expired() ? cache.erase(it) : std::next(it);
    cache[key] = p;
    return p;
}

const Plan& plan_argument(const py::handle& value, const std::string& what) {
    if (!py::isinstance<Plan>(value)) throw InputError(fmt::format("{}: expected jacobid.plan()'s result, got {}", what, type_name(value)));
    return value.cast<const Plan&>();
}

std::shared_ptr<Factor> make_factor(const py::object& robot_value, const py::object& source, const py::object& plan_value, const py::args& extra,
                                    const py::kwargs& keywords) {
    refuse_extra_positional("factor", extra, {"robot", "log", "plan"});
    refuse_unknown_keywords("factor", keywords, {"robot", "log", "plan"});
    const Plan& plan = plan_argument(plan_value, "plan");
    const Robot r = robot_of(robot_value);
    if (r.model->parameter_names() != plan.robot.model->parameter_names()) {
        throw InputError(fmt::format("robot: {} ({} parameters), but the plan is of {} ({} parameters); factor a log with its plan's robot",
                                     r.description.source, r.model->parameter_count(), plan.robot.description.source,
                                     plan.robot.model->parameter_count()));
    }
    if (several_logs(source)) throw InputError("log: a list; a factor is of one log (merge the factors of several)");
    auto f = std::make_shared<Factor>();
    f->plan = plan_value.cast<std::shared_ptr<Plan>>();
    options::IdentifyOptions o = plan.o;
    job::LogSource log = log_source(plan.robot, source, o.time_column, "--in");
    o.inputs = {log.name};
    job::check_identify_files(o, plan.robot.description, {});
    {
        py::gil_scoped_release unlocked;
        const auto start = std::chrono::steady_clock::now();
        const job::InputLogs in = job::read_inputs({std::move(log)}, plan.robot.description, o, plan.grid_period);
        f->data.parse_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        for (const identify::LogColumns& c : in.columns) job::check_sample_period(o.first_input(), c.sample_period, plan.reference, plan.sample_period);
        f->data.inputs = o.inputs;
        f->data.pieces = in.pieces;
        for (identify::SegmentReport& piece : f->data.pieces) piece.log = o.first_input();  // as identify --in a --in b names each log's lines
        f->data.names = in.names;
        for (const job::MethodPlan& m : plan.methods) f->data.methods.push_back(job::factor_log(m, *plan.robot.model, in.columns, o.threads));
    }
    return f;
}

// The factors in their order, checked to share one plan and no log.
std::vector<std::shared_ptr<Factor>> factor_list(const py::handle& value) {
    const std::string expected = "expected a non-empty list of jacobid.factor() results";
    if (!py::isinstance<py::list>(value) && !py::isinstance<py::tuple>(value)) throw InputError(fmt::format("factors: {}, got {}", expected, type_name(value)));
    std::vector<std::shared_ptr<Factor>> factors;
    std::set<std::string> logs;
    for (const py::handle item : py::reinterpret_borrow<py::sequence>(value)) {
        const std::size_t k = factors.size();
        if (!py::isinstance<Factor>(item)) throw InputError(fmt::format("factors[{}]: {}, got {}", k, expected, type_name(item)));
        factors.push_back(item.cast<std::shared_ptr<Factor>>());
        if (factors.back()->plan->bytes != factors.front()->plan->bytes) {
            throw InputError(fmt::format("factors[{}] ({}): made with another plan than factors[0]; the factors of one merge share one jacobid.plan", k,
                                         job::log_names(factors.back()->data.inputs)));
        }
        for (const std::string& log : factors.back()->data.inputs) {
            // Logs given as arrays are all named --in; a file twice would count its equations twice.
            if (log != "--in" && !logs.insert(log).second) throw InputError(fmt::format("factors[{}]: the log {} is in an earlier factor too; its equations would count twice", k, log));
        }
    }
    if (factors.empty()) throw InputError(fmt::format("factors: {}, got an empty list", expected));
    return factors;
}

// identify's result from the merged factors of every log: the job's solve, --physical / --essential and its end.
nlohmann::json solve_merged(const Plan& plan, FactorData merged) {
    options::IdentifyOptions o = plan.o;
    o.inputs = merged.inputs;
    const robot::RobotDescription& robot = plan.robot.description;
    const robot::RobotModel& model = *plan.robot.model;
    job::IdentifyJobResult out;
    out.inputs = merged.inputs;
    out.model_name = model.model_name();
    out.parse_seconds = merged.parse_seconds;
    out.ctx = job::report_context(robot, model, o, {}, nullptr, false);
    std::vector<job::MethodPlan> methods = plan.decoded();  // solve_plan consumes its plan
    for (std::size_t m = 0; m < methods.size(); ++m) {
        identify::finish_segments(merged.methods[m], methods[m].segments);
        const identify::SolveOptions solve = method_settings(o, methods[m].method).solve;
        identify::IdentifiedLog fit = job::solve_plan(std::move(methods[m]), std::move(merged.methods[m]), merged.pieces, merged.names, model, solve);
        job::complete_fit(fit, robot, model, o, solve, {});
        out.results.push_back(std::move(fit.result));
    }
    job::finish_identify(out, robot, o);
    return job::to_json(out);
}

py::object merge(const py::object& factors_value, const py::args& extra, const py::kwargs& keywords) {
    refuse_extra_positional("merge", extra, {"factors"});
    refuse_unknown_keywords("merge", keywords, {"factors", "solve"});
    bool solve = true;
    if (keywords.contains("solve")) {
        if (!is_bool(keywords["solve"])) throw InputError(fmt::format("solve: expected True or False, got {}", type_name(keywords["solve"])));
        solve = keywords["solve"].cast<bool>();
    }
    const std::vector<std::shared_ptr<Factor>> factors = factor_list(factors_value);
    const std::shared_ptr<const Plan> plan = factors.front()->plan;
    auto merged = std::make_shared<Factor>();
    merged->plan = plan;
    nlohmann::json result;
    {
        py::gil_scoped_release unlocked;
        FactorData& total = merged->data;
        // The ordered tree identify merges its logs by, so that a list merged here is the command's bit for bit.
        std::vector<identify::OrderedMerge> trees(plan->methods.size(), identify::OrderedMerge(plan->o.pipeline.plot_rows));
        for (const auto& f : factors) {
            const FactorData& part = f->data;
            total.inputs.insert(total.inputs.end(), part.inputs.begin(), part.inputs.end());
            total.pieces.insert(total.pieces.end(), part.pieces.begin(), part.pieces.end());
            total.names.insert(total.names.end(), part.names.begin(), part.names.end());
            total.parse_seconds += part.parse_seconds;
            for (std::size_t m = 0; m < trees.size(); ++m) trees[m].add(part.methods[m]);
        }
        for (identify::OrderedMerge& tree : trees) total.methods.push_back(tree.result());
        if (solve) result = solve_merged(*plan, std::move(total));
    }
    if (!solve) return py::cast(merged);
    return to_python(result);
}

std::vector<std::string> method_names(const Plan& p) {
    std::vector<std::string> names;
    for (const job::MethodPlan& m : p.methods) names.emplace_back(identify::to_string(m.method));
    return names;
}

}  // namespace

void bind_fleet(py::module_& m) {
    py::class_<Plan, std::shared_ptr<Plan>>(m, "Plan", "identify's set-up resolved once for every log identified together (jacobid.plan).")
        .def_property_readonly("robot", [](const Plan& p) { return p.robot; }, "the Robot it was planned for")
        .def_property_readonly("options", [](const Plan& p) { return py::dict(p.keywords); }, "identify's keywords it was planned with")
        .def_property_readonly("reference", [](const Plan& p) { return text_of(p.reference); }, "the log the set-up was resolved on")
        .def_property_readonly("sample_period", [](const Plan& p) { return p.sample_period; }, "s, of every log of the plan")
        .def_property_readonly("methods", &method_names, "the methods (jacobi, butterworth), one set-up each")
        .def_property_readonly("nbytes", [](const Plan& p) { return p.bytes.size(); }, "bytes of the resolved set-up as it travels")
        .def(py::pickle(&plan_state, &cached_plan_of_state))
        .def("__repr__", [](const Plan& p) {
            return text_of(fmt::format("Plan(methods={}, reference={}, sample_period={:g}, nbytes={})", joined(method_names(p)), p.reference,
                                       p.sample_period, p.bytes.size()));
        });
    py::class_<Factor, std::shared_ptr<Factor>>(m, "Factor", "What one log (or several, merged) reduced to with a plan (jacobid.factor).")
        .def_property_readonly("logs", [](const Factor& f) { return f.data.inputs; }, "the logs it holds, in order")
        .def_property_readonly("plan", [](const Factor& f) { return std::const_pointer_cast<Plan>(f.plan); }, "the Plan it was made with")
        .def_property_readonly("rows", [](const Factor& f) { return f.data.methods.front().rows; },
                               "equations per joint of each piece (the first method's; 0 for a piece not used)")
        .def_property_readonly("nbytes", [](const Factor& f) { return encode_factor(f.data).size(); },
                               "bytes of the factor as it travels (its triangles, lagged products and report lines; the plan apart)")
        .def(py::pickle([](const Factor& f) { return py::make_tuple(std::const_pointer_cast<Plan>(f.plan), py::bytes(encode_factor(f.data))); },
                        [](const py::tuple& state) {
                            if (state.size() != 2) throw InputError("factor: not a pickled jacobid factor");
                            auto f = std::make_shared<Factor>();
                            f->plan = state[0].cast<std::shared_ptr<Plan>>();
                            f->data = decode_factor(state[1].cast<std::string>());
                            return f;
                        }))
        .def("__repr__", [](const Factor& f) { return text_of(fmt::format("Factor(logs={}, nbytes={})", f.data.inputs.size(), encode_factor(f.data).size())); });
    const py::object none = py::none();
    m.def("_plan", &make_plan, py::arg("robot") = none, py::arg("log") = none);
    m.def("_factor", &make_factor, py::arg("robot") = none, py::arg("log") = none, py::arg("plan") = none);
    m.def("_merge", &merge, py::arg("factors") = none);
}

}  // namespace jacobid::python
