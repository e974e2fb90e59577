// SPDX-License-Identifier: MIT
// The runs of `jacobid montecarlo` one by one, for jacobid.fleet.montecarlo to run as Dask tasks, and the table
// of their estimates: the study's own pieces (montecarlo::run_one, collect_study, format_table / to_json) with the
// command's options (options/montecarlo_options.hpp), so the table is the command's.
#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "cli_arguments.hpp"
#include "core/errors.hpp"
#include "json_to_python.hpp"
#include "montecarlo/study.hpp"
#include "montecarlo/study_report.hpp"
#include "options/montecarlo_options.hpp"
#include "options/output_file.hpp"
#include "python_values.hpp"

namespace py = pybind11;

namespace jacobid::python {
namespace {

// The command's options from keywords (robot: a path or None, as --robot); `known` the function's own arguments.
options::MonteCarloOptions montecarlo_options(const py::object& robot, const py::kwargs& keywords, const std::vector<std::string>& known) {
    options::MonteCarloOptions o;
    CLI::App app("", "montecarlo");
    options::add_montecarlo_options(&app, o);
    parse_keywords(app, keywords, known);
    if (!robot.is_none()) {
        o.robot = path_text(robot, "robot");
        options::check_outputs({}, {{"--robot", o.robot}});
    }
    return o;
}

// Runs first .. first + count - 1: per run, per method, the estimates and their std as numpy arrays.
py::list montecarlo_runs(const py::object& robot, int first, int count, const py::kwargs& keywords) {
    const montecarlo::StudySettings s = options::study_settings(montecarlo_options(robot, keywords, {"robot", "first", "count"}));
    if (first < 0 || count < 1 || first + count > s.runs) {
        throw InputError(fmt::format("runs {} .. {}: outside the study's {} runs", first, first + count - 1, s.runs));
    }
    py::list out;
    for (int k = first; k < first + count; ++k) {
        montecarlo::RunEstimates r;
        {
            py::gil_scoped_release unlocked;
            r = montecarlo::run_one(s, k);
        }
        py::list methods;
        const auto array = [](const Eigen::VectorXd& v) { return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data()); };
        for (std::size_t m = 0; m < r.x.size(); ++m) methods.append(py::make_tuple(array(r.x[m]), array(r.std_dev[m])));
        out.append(methods);
    }
    return out;
}

std::vector<double> values_of(const py::handle& array, std::size_t size, const std::string& what) {
    std::vector<double> v = py::cast<std::vector<double>>(array);
    if (v.size() != size) throw InputError(fmt::format("{}: {} values, expected {} (the model's parameters)", what, v.size(), size));
    return v;
}

// The study of every run (montecarlo_runs' items in run order) as the command prints it: its table, or its JSON.
py::object montecarlo_table(const py::object& robot, const py::list& runs_done, double seconds, int workers, const std::string& format,
                            const py::kwargs& keywords) {
    const options::MonteCarloOptions o = montecarlo_options(robot, keywords, {"robot", "estimates", "seconds", "workers", "format"});
    const py::list& runs = runs_done;
    montecarlo::StudySettings s = options::study_settings(o);
    if (static_cast<int>(runs.size()) != s.runs) throw InputError(fmt::format("estimates: {} runs, expected the study's {}", runs.size(), s.runs));
    const std::size_t parameters = static_cast<std::size_t>(robot::make_robot_model(s.robot)->parameter_count());
    std::vector<montecarlo::RunEstimates> estimates;
    for (std::size_t k = 0; k < runs.size(); ++k) {
        const py::list methods = runs[k].cast<py::list>();
        montecarlo::RunEstimates& r = estimates.emplace_back();
        for (std::size_t m = 0; m < methods.size(); ++m) {
            const py::tuple xs = methods[m].cast<py::tuple>();
            const std::string what = fmt::format("estimates[{}][{}]", k, m);
            const std::vector<double> x = values_of(xs[0], parameters, what), sd = values_of(xs[1], parameters, what);
            r.x.push_back(Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size())));
            r.std_dev.push_back(Eigen::Map<const Eigen::VectorXd>(sd.data(), static_cast<Eigen::Index>(sd.size())));
        }
        if (r.x.size() != s.methods.size()) throw InputError(fmt::format("estimates[{}]: {} methods, expected {}", k, r.x.size(), s.methods.size()));
    }
    const montecarlo::Study study = montecarlo::collect_study(s, std::move(estimates), seconds, workers);
    const montecarlo::StudyContext context = options::study_context(o, s);
    if (format == "json") return to_python(montecarlo::to_json(study, context));
    if (format != "table") throw InputError(fmt::format("format: '{}'; expected table or json", format));
    return text_of(montecarlo::format_table(study, context));
}

}  // namespace

void bind_montecarlo(py::module_& m) {
    m.def("_montecarlo_runs", &montecarlo_runs, py::arg("robot"), py::arg("first"), py::arg("count"));
    m.def("_montecarlo_table", &montecarlo_table, py::arg("robot"), py::arg("estimates"), py::arg("seconds"), py::arg("workers"), py::arg("format"));
}

}  // namespace jacobid::python
