// SPDX-License-Identifier: MIT
// lib/ through the host's checked wrappers: kernel options are parsed by the CLI's definitions (options/kernel_options),
// so a bad value raises the message `jacobid kernel` prints. Every argument is taken as a plain Python object and
// checked by the module's one layer (checked_array for arrays, parse_keywords for everything else, the scalar
// arguments given by position included), so pybind11 never converts (or refuses) a user's value itself.
#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <pybind11/complex.h>
#include <pybind11/stl.h>

#include <array>
#include <memory>

#include "bindings.hpp"
#include "options/kernel_description.hpp"
#include "options/kernel_options.hpp"
#include "options/option_checks.hpp"
#include "cli_arguments.hpp"
#include "core/errors.hpp"
#include "json_to_python.hpp"
#include "jacobid/differentiator_bank.hpp"
#include "jacobid/frequency_response.hpp"
#include "numpy_views.hpp"
#include "signal/baseline_response.hpp"
#include "signal/differentiation.hpp"

namespace py = pybind11;

namespace jacobid::python {
namespace {

// The keywords with the scalar arguments `function` was given by position added, to be parsed with them.
py::dict with_arguments(const py::kwargs& keywords, std::initializer_list<std::pair<const char*, py::object>> arguments) {
    py::dict all(keywords);
    for (const auto& [name, value] : arguments) all[name] = value;
    return all;
}

// The kernel of `jacobid kernel` options given as keywords (order, kappa, mu, q, window, ts, xi, discretization)
// to `function`, whose own `arguments` are named among its keywords.
KernelParams kernel_params(const py::dict& keywords, const std::string& function, const std::vector<std::string>& arguments = {}) {
    options::KernelOptions options;
    CLI::App app("", function);
    options::add_kernel_options(&app, options, true, true);
    app.get_option("--window")->required();
    parse_keywords(app, keywords, arguments);
    return options::to_kernel_params(options);
}

py::dict kernel(const py::args& extra, const py::kwargs& keywords) {
    refuse_extra_positional("kernel", extra, {});
    const KernelParams p = kernel_params(keywords, "kernel");
    std::vector<double> weights = options::design_kernel_or_throw(p);
    py::dict d = to_python(options::describe_kernel(p, weights));
    d["weights"] = owning_array(std::move(weights));
    return d;
}

py::dict frequency_response(const py::object& weights_value, const py::object& ts_value, const py::object& frequencies_value, const py::args& extra,
                            const py::kwargs& keywords) {
    refuse_extra_positional("frequency_response", extra, {"weights", "ts", "frequencies"});
    double ts = 0.0;
    CLI::App app("", "frequency_response");
    app.add_option("--ts", ts)->check(options::positive_number())->required();
    parse_keywords(app, with_arguments(keywords, {{"ts", ts_value}}), {"weights", "frequencies"});
    const DoubleArray weights = checked_array(weights_value, "weights", Layout::Samples);
    const DoubleArray frequencies = checked_array(frequencies_value, "frequencies", Layout::Samples);
    const Span<const double> w = samples_of(weights);
    const Span<const double> f = samples_of(frequencies);
    py::array_t<std::complex<double>> response(f.size());
    std::vector<double> magnitude(f.size()), phase(f.size()), group_delay(f.size());
    auto* h = response.mutable_data();
    for (std::size_t i = 0; i < f.size(); ++i) {
        const FrequencyPoint point = fir_response(w, ts, f[i]);
        h[i] = point.response;
        magnitude[i] = point.magnitude;
        phase[i] = point.phase;
        group_delay[i] = point.group_delay;
    }
    py::dict d;
    d["frequency"] = frequencies;
    d["response"] = response;
    d["magnitude"] = owning_array(std::move(magnitude));
    d["phase"] = owning_array(std::move(phase));
    d["group_delay"] = owning_array(std::move(group_delay));
    return d;
}

// What a differentiator returns: values[i] is the estimate at input sample first_index + i.
struct PyEstimate {
    py::array_t<double> values;
    double first_index = 0.0;
};

PyEstimate as_python(signal::Estimate&& e) { return {owning_array(std::move(e.values)), e.first_index}; }

PyEstimate differentiate(const py::object& x_value, const py::args& extra, const py::kwargs& keywords) {
    refuse_extra_positional("differentiate", extra, {"x"});
    const KernelParams p = kernel_params(keywords, "differentiate", {"x"});
    const DoubleArray x = checked_array(x_value, "x", Layout::Samples);
    const std::vector<double> weights = options::design_kernel_or_throw(p);
    const Span<const double> samples = samples_of(x);
    signal::Estimate e;
    {
        // The samples are read in place; other Python threads may run meanwhile.
        py::gil_scoped_release unlocked;
        e = signal::jacobi_estimate(p, weights, samples, "x");
    }
    return as_python(std::move(e));
}

PyEstimate butterworth_euler(const py::object& x_value, const py::object& ts_value, const py::object& spec_value, const py::object& order_value,
                             const py::object& crop_value, const py::args& extra, const py::kwargs& keywords) {
    refuse_extra_positional("butterworth_euler", extra, {"x", "ts", "butterworth", "order", "crop"});
    double ts = 0.0;
    std::string spec;
    int order = 1;
    std::size_t crop = 0;
    CLI::App app("", "butterworth_euler");
    app.add_option("--ts", ts)->check(options::positive_number())->required();
    app.add_option("--butterworth", spec)->required();
    app.add_option("--order", order)->check(options::whole_number_in(0, 2));
    app.add_option("--crop", crop)->check(options::whole_number_from(0));
    parse_keywords(app, with_arguments(keywords, {{"ts", ts_value}, {"butterworth", spec_value}, {"order", order_value}, {"crop", crop_value}}), {"x"});
    const signal::ButterworthEuler bw = signal::parse_butterworth_spec(spec, "butterworth", ts);
    const DoubleArray x = checked_array(x_value, "x", Layout::Samples);
    const Span<const double> samples = samples_of(x);
    const std::size_t edge = app.count("--crop") == 0 ? signal::butterworth_edge_samples(bw.cutoff_hz, ts) : crop;
    const std::vector<double> copy(samples.begin(), samples.end());  // the baseline's API takes a vector
    return as_python(signal::butterworth_euler_estimate(bw.sos, order, ts, copy, edge, "x"));
}

// The streaming bank (lib/differentiator_bank.hpp) for 1 to kMaxJoints joints, up to kCapacity taps per kernel.
constexpr int kMaxJoints = 8;
constexpr std::size_t kCapacity = 4096;

class Bank {
public:
    virtual ~Bank() = default;
    virtual BankConfigResult configure(const KernelParams (&channels)[kChannelCount]) = 0;
    virtual py::dict step(const Matrix& q, const Matrix& tau) = 0;
    virtual void reset() = 0;
    virtual std::size_t delay_samples() const = 0;
    virtual std::size_t warmup_samples() const = 0;
    virtual int joints() const = 0;
};

template <int Joints>
class FixedBank final : public Bank {
public:
    BankConfigResult configure(const KernelParams (&channels)[kChannelCount]) override {
        std::array<JointFilterConfig, Joints> config{};
        for (auto& joint : config) {
            for (int c = 0; c < kChannelCount; ++c) joint.params[static_cast<std::size_t>(c)] = channels[c];
        }
        return bank_.configure(config);
    }
    py::dict step(const Matrix& q, const Matrix& tau) override {
        const std::size_t n = q.rows;
        py::array_t<double> position = new_matrix(n, Joints), velocity = new_matrix(n, Joints), acceleration = new_matrix(n, Joints),
                            torque = new_matrix(n, Joints), raw_position = new_matrix(n, Joints);
        py::array_t<std::uint64_t> sample_index(n);
        py::array_t<bool> valid(n);
        double* out[] = {position.mutable_data(), velocity.mutable_data(), acceleration.mutable_data(), torque.mutable_data(),
                         raw_position.mutable_data()};
        auto* index = sample_index.mutable_data();
        auto* ok = valid.mutable_data();
        {
            py::gil_scoped_release unlocked;
            typename DifferentiatorBank<double, Joints, kCapacity>::Vector qi, ti;
            BankOutput<double, Joints> o;
            for (std::size_t r = 0; r < n; ++r) {
                for (int j = 0; j < Joints; ++j) {
                    qi[j] = q.at(r, static_cast<std::size_t>(j));
                    ti[j] = tau.at(r, static_cast<std::size_t>(j));
                }
                bank_.step(qi, ti, o);
                const typename BankOutput<double, Joints>::Vector* rows[] = {&o.position, &o.velocity, &o.acceleration, &o.torque, &o.raw_position};
                for (int k = 0; k < 5; ++k) {
                    for (int j = 0; j < Joints; ++j) out[k][r * Joints + static_cast<std::size_t>(j)] = (*rows[k])[j];
                }
                index[r] = o.sample_index;
                ok[r] = o.valid;
            }
        }
        py::dict d;
        d["position"] = position;
        d["velocity"] = velocity;
        d["acceleration"] = acceleration;
        d["torque"] = torque;
        d["raw_position"] = raw_position;
        d["sample_index"] = sample_index;
        d["valid"] = valid;
        return d;
    }
    void reset() override { bank_.reset(); }
    std::size_t delay_samples() const override { return bank_.delay_samples(); }
    std::size_t warmup_samples() const override { return bank_.warmup_samples(); }
    int joints() const override { return Joints; }

private:
    DifferentiatorBank<double, Joints, kCapacity> bank_;
};

template <int Joints>
std::unique_ptr<Bank> bank_of(int joints) {
    if constexpr (Joints > kMaxJoints) {
        throw InputError(fmt::format("joints {}: expected 1 to {} joints", joints, kMaxJoints));
    } else {
        if (joints == Joints) return std::make_unique<FixedBank<Joints>>();
        return bank_of<Joints + 1>(joints);
    }
}

// Bank(joints, ts=..., window=..., kappa=..., ...): one kernel per channel (order 0, 1, 2) with the same
// options; windows=(T0, T1, T2) gives each channel its own window.
std::unique_ptr<Bank> make_bank(const py::object& joints_value, const py::args& extra, const py::kwargs& keywords) {
    refuse_extra_positional("Bank", extra, {"joints"});
    options::KernelOptions options;
    int joints = 0;
    std::vector<double> windows;
    CLI::App app("", "Bank");
    options::add_kernel_options(&app, options, true, true);
    app.add_option("--joints", joints)->check(options::whole_number_in(1, kMaxJoints))->required();
    app.add_option("--windows", windows)->delimiter(',')->check(options::positive_number());
    parse_keywords(app, with_arguments(keywords, {{"joints", joints_value}}));
    if (app.count("--order") != 0) throw InputError("order: a bank has one kernel per order (0, 1, 2); give window or windows");
    if (app.count("--window") != 0 && app.count("--windows") != 0) throw InputError("--window and --windows: give one of them");
    if (app.count("--windows") != 0 && windows.size() != static_cast<std::size_t>(kChannelCount)) {
        throw InputError(fmt::format("--windows: expected {} windows (orders 0, 1, 2), got {}", kChannelCount, windows.size()));
    }
    if (app.count("--window") == 0 && app.count("--windows") == 0) throw InputError("--window is required (or --windows, one per order 0, 1, 2)");
    std::unique_ptr<Bank> bank = bank_of<1>(joints);
    KernelParams channels[kChannelCount];
    for (int c = 0; c < kChannelCount; ++c) {
        options::KernelOptions channel = options;
        channel.order = c;
        if (!windows.empty()) channel.window = windows[static_cast<std::size_t>(c)];
        channels[c] = options::to_kernel_params(channel);
    }
    const BankConfigResult r = bank->configure(channels);
    if (r.status != BankStatus::Ok) {
        std::string why = describe(r.status);
        if (r.status == BankStatus::InvalidKernel) why += fmt::format(": {}", describe(r.kernel_status));
        throw InputError(fmt::format("bank channel of order {}: {}", r.channel, why));
    }
    return bank;
}

// Samples x joints of positions or torques for `bank`: checked, and a one-dimensional array only for one joint
// (for several it is one sample or one joint's samples: the caller must say which).
Matrix bank_input(const Bank& bank, const DoubleArray& array, const std::string& what) {
    const auto joints = static_cast<std::size_t>(bank.joints());
    if (array.ndim() == 1 && joints > 1) {
        throw InputError(fmt::format("{0}: a one-dimensional array of {1} values; expected samples x joints (1 x {2} for one sample: {0}.reshape(1, -1))",
                                     what, array.shape(0), joints));
    }
    const Matrix m = matrix_of(array);
    if (m.columns != joints) throw InputError(fmt::format("{}: {} columns, the bank has {} joints", what, m.columns, joints));
    return m;
}

py::dict step(Bank& bank, const py::object& q_value, const py::object& tau_value, const py::args& extra, const py::kwargs& keywords) {
    refuse_extra_positional("step", extra, {"q", "tau"});
    refuse_unknown_keywords("step", keywords, {"q", "tau"});
    const DoubleArray q = checked_array(q_value, "q", Layout::SamplesByJoints), tau = checked_array(tau_value, "tau", Layout::SamplesByJoints);
    const Matrix qm = bank_input(bank, q, "q"), tm = bank_input(bank, tau, "tau");
    if (tm.rows != qm.rows) throw InputError(fmt::format("tau: {} samples, q has {}", tm.rows, qm.rows));
    return bank.step(qm, tm);
}

}  // namespace

void bind_core(py::module_& m) {
    m.def("kernel", &kernel,
          "kernel(*, window, ts, order=1, kappa=6, mu=6, q=2, xi='0', discretization='trapezoidal') -> dict\n\n"
          "The FIR weights of one Jacobi differentiator, as `jacobid kernel --format json` describes them: keys parameters, "
          "taps, effective_window, delay_samples, delay_seconds, cutoff_hz, weights_order, weights (a numpy array, oldest "
          "sample first). The keywords are the command's options (xi: a number in [-1, 1], 'central', 'causal' or 'delayed').");
    // Every argument defaults to None, so that a missing one reaches the checks ("x: expected an array of numbers,
    // got None", "--ts is required") instead of pybind11's "incompatible function arguments".
    const py::object none = py::none();
    m.def("frequency_response", &frequency_response, py::arg("weights") = none, py::arg("ts") = none, py::arg("frequencies") = none,
          "frequency_response(weights, ts, frequencies) -> dict\n\n"
          "H(f) of FIR weights (oldest sample first) sampled every ts seconds, at each frequency in Hz: keys frequency, "
          "response (complex), magnitude, phase (rad), group_delay (s), numpy arrays.");
    py::class_<PyEstimate>(m, "Estimate", "A differentiated signal: values[i] estimates the input sample first_index + i.")
        .def_readonly("values", &PyEstimate::values, "the estimates (numpy float64 array)")
        .def_readonly("first_index", &PyEstimate::first_index, "input sample index (fractional for a non-integer delay) of values[0]")
        .def("__repr__", [](const PyEstimate& e) { return fmt::format("Estimate(values=<{} samples>, first_index={})", e.values.size(), e.first_index); });
    m.def("differentiate", &differentiate, py::arg("x") = none,
          "differentiate(x, *, ts, window, order=1, kappa=6, mu=6, q=2, xi='0', discretization='trapezoidal') -> Estimate\n\n"
          "The Jacobi estimate of the order-th derivative of the uniformly sampled x (float64, read in place when "
          "C-contiguous), through the same batch differentiation as `jacobid differentiate` (FFT for long kernels). "
          "Only the samples with a full window are returned: values[i] refers to input sample first_index + i.");
    m.def("butterworth_euler", &butterworth_euler, py::arg("x") = none, py::arg("ts") = none, py::arg("butterworth") = none, py::arg("order") = 1,
          py::arg("crop") = none,
          "butterworth_euler(x, ts, butterworth, order=1, crop=None) -> Estimate\n\n"
          "The baseline of `jacobid differentiate --method butterworth`: forward-backward Butterworth ('ORDER:CUTOFF_HZ', "
          "e.g. '4:5'), then the central Euler difference of order 0, 1 or 2; crop samples (default 3 / cutoff) dropped "
          "at each end.");
    py::class_<Bank>(m, "Bank",
                     "The streaming differentiator bank of the firmware (lib/differentiator_bank.hpp): per joint the position, "
                     "velocity and acceleration estimates and the raw torque, all aligned to one common delay.")
        .def(py::init(&make_bank), py::arg("joints") = none,
             "Bank(joints, *, ts, window=None, windows=None, kappa=6, mu=6, q=2, xi='0', discretization='trapezoidal')\n\n"
             "Designs one kernel per channel (orders 0, 1, 2) from `jacobid kernel`'s options; windows=(T0, T1, T2) gives "
             "each channel its own window. 1 to 8 joints, up to 4096 taps per kernel.")
        .def("step", &step, py::arg("q") = none, py::arg("tau") = none,
             "step(q, tau) -> dict\n\n"
             "Feeds samples x joints arrays of positions and torques, one row per cycle, and returns per row: position, "
             "velocity, acceleration, torque, raw_position (samples x joints), sample_index (the input sample each row "
             "refers to) and valid (False during warm-up). The history carries over to the next call.")
        .def("reset",
             [](Bank& bank, const py::args& extra, const py::kwargs& keywords) {
                 refuse_extra_positional("reset", extra, {});
                 refuse_unknown_keywords("reset", keywords, {});
                 bank.reset();
             },
             "Clears the history (e.g. after a gap); the kernels stay.")
        .def_property_readonly("delay_samples", &Bank::delay_samples, "common delay of every output, in samples")
        .def_property_readonly("warmup_samples", &Bank::warmup_samples, "cycles until the first valid output")
        .def_property_readonly("joints", &Bank::joints);
}

}  // namespace jacobid::python
