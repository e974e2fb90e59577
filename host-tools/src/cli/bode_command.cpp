// SPDX-License-Identifier: MIT
// jacobid bode: frequency response (magnitude, phase, group delay) of one or several differentiators
// against the ideal (2 pi f)^n, as CSV and a PNG plot (the paper's Fig. 2 and Fig. 3).
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "cli/command.hpp"
#include "options/kernel_options.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"
#include "jacobid/frequency_response.hpp"
#include "plot/gnuplot.hpp"
#include "signal/baseline_response.hpp"

namespace jacobid::cli {
namespace {

// Frequency points over all curves: 1e7 (a GB of CSV) is far beyond what a plot resolves.
constexpr double kMaxCurvePoints = 1e7;

struct BodeOptions {
    KernelOptions kernel;
    std::vector<std::string> compare;
    std::vector<std::string> butterworth;
    double fmax = 0.0;
    int points = 2000;
    std::string csv = "-";
    std::string png;
    bool db = false;
};

struct Curve {
    std::string label;
    std::vector<std::complex<double>> response;
    std::vector<double> group_delay;
    std::string summary;
};

std::string column_label(std::string s) {
    std::replace(s.begin(), s.end(), ' ', '_');
    return s;
}

void run(const BodeOptions& o) {
    check_outputs({{"--csv", o.csv}, {"--png", o.png}});
    std::vector<KernelParams> configs{to_kernel_params(o.kernel)};
    for (const auto& spec : o.compare) {
        KernelSource source;
        source.overrides = fmt::format("--compare '{}'", spec);
        configs.push_back(to_kernel_params(with_overrides(o.kernel, spec, "--compare"), source));
    }
    const int order = configs.front().order;
    const double ts = configs.front().sample_period;
    for (const auto& p : configs) {
        if (p.order != order || p.sample_period != ts) {
            throw InputError("--compare: every configuration on one plot must share --order and --ts (the ideal curve and the frequency axis)");
        }
    }
    const double nyquist = 0.5 / ts;
    const double fmax = o.fmax > 0 ? o.fmax : nyquist;
    if (fmax > nyquist * (1 + 1e-12)) throw InputError(fmt::format("--fmax: {} Hz is above the Nyquist frequency {} Hz", fmax, nyquist));
    // Each point holds a response and a group delay per curve, and about 75 bytes of CSV per curve.
    refuse_oversized(fmt::format("--points {}", o.points), static_cast<double>(o.points) * static_cast<double>(configs.size() + o.butterworth.size()),
                     kMaxCurvePoints, "curve points", 100.0, "lower --points");
    std::vector<double> f(static_cast<std::size_t>(o.points));
    for (std::size_t i = 0; i < f.size(); ++i) f[i] = fmax * static_cast<double>(i + 1) / static_cast<double>(f.size());

    std::vector<Curve> curves;
    for (const auto& p : configs) {
        const std::vector<double> w = design_kernel_or_throw(p);
        Curve c;
        c.label = "Jacobi " + kernel_label(p);
        for (double fi : f) {
            const FrequencyPoint r = fir_response(Span<const double>(w), ts, fi);
            c.response.push_back(r.response);
            c.group_delay.push_back(r.group_delay);
        }
        const Cutoff cut = find_cutoff(Span<const double>(w), ts, order);
        c.summary = fmt::format("{}: {} taps, delay {:.6g} s, cutoff {}", c.label, w.size(), delay_samples(p) * ts,
                                cut.found ? fmt::format("{:.4g} Hz", cut.frequency) : "above Nyquist");
        curves.push_back(std::move(c));
    }
    for (const auto& spec : o.butterworth) {
        const signal::ButterworthEuler bw = signal::parse_butterworth_spec(spec, "--butterworth", ts);
        Curve c;
        c.label = fmt::format("Butterworth order {} {:g} Hz fwd-bwd + Euler", bw.order, bw.cutoff_hz);
        for (double fi : f) {
            c.response.push_back(signal::butterworth_euler_response(bw, order, ts, fi));
            c.group_delay.push_back(0.0);  // zero phase (forward-backward) and central differences
        }
        c.summary = c.label + ": zero phase, no delay (off-line only)";
        curves.push_back(std::move(c));
    }
    for (const auto& c : curves) fmt::print(stderr, "{}\n", c.summary);

    std::string csv = "f_hz,ideal_mag";
    for (const auto& c : curves) {
        const std::string l = column_label(c.label);
        csv += fmt::format(",{0}_mag,{0}_phase_rad,{0}_group_delay_s", l);
    }
    csv += "\n";
    for (std::size_t i = 0; i < f.size(); ++i) {
        csv += fmt::format("{:.17g},{:.17g}", f[i], ideal_magnitude(order, f[i]));
        for (const auto& c : curves) {
            csv += fmt::format(",{:.17g},{:.17g},{:.17g}", std::abs(c.response[i]), std::arg(c.response[i]), c.group_delay[i]);
        }
        csv += "\n";
    }
    write_output(o.csv, csv);

    if (!o.png.empty()) {
        auto magnitude = [&](double m) { return o.db ? 20.0 * std::log10(std::max(m, 1e-300)) : m; };
        plot::Panel mag{fmt::format("Magnitude, derivative order {}", order), "frequency [Hz]", o.db ? "|H| [dB]" : "|H|", false, !o.db, {}, ""};
        plot::Panel phase{"Phase", "frequency [Hz]", "arg H [rad]", false, false, {}, ""};
        plot::Series ideal{order == 0 ? "ideal (1)" : fmt::format("ideal (2 pi f)^{}", order), f, {}, "lines dt 2 lw 2 lc rgb 'black'"};
        for (double fi : f) ideal.y.push_back(magnitude(ideal_magnitude(order, fi)));
        mag.series.push_back(ideal);
        for (std::size_t i = 0; i < curves.size(); ++i) {
            const Curve& c = curves[i];
            const std::string style = fmt::format("lines lw 1.5 lc {}", i + 1);  // same colour in both panels
            plot::Series m{c.label, f, {}, style};
            plot::Series ph{c.label, f, {}, style};
            for (const auto& h : c.response) {
                m.y.push_back(magnitude(std::abs(h)));
                ph.y.push_back(std::arg(h));
            }
            mag.series.push_back(std::move(m));
            phase.series.push_back(std::move(ph));
        }
        if (!o.db) mag.extra = "set format y '10^{%T}'\n";
        plot::render_png(o.png, {mag, phase});
        fmt::print(stderr, "wrote {}\n", o.png);
    }
}

}  // namespace

void add_bode_command(CLI::App& app) {
    auto o = std::make_shared<BodeOptions>();
    CLI::App* cmd = app.add_subcommand("bode", "frequency response of Jacobi differentiators (and Butterworth + Euler) against the ideal (2 pi f)^n");
    add_kernel_options(cmd, o->kernel, true, true);
    cmd->get_option("--window")->required();
    cmd->add_option("--compare", o->compare,
                    "another Jacobi configuration on the same plot, as overrides of the main one, e.g. 'kappa=12,mu=12,q=6' (repeatable)");
    cmd->add_option("--butterworth", o->butterworth,
                    "overlay a forward-backward Butterworth low-pass + central Euler difference of the same order, as ORDER:CUTOFF_HZ, e.g. 6:25 (repeatable)");
    cmd->add_option("--fmax", o->fmax, "highest frequency in Hz (default: Nyquist)")->check(positive_number());
    cmd->add_option("--points", o->points, "number of frequency points")->check(whole_number_from(2))->capture_default_str();
    cmd->add_option("--csv", o->csv, "CSV output (f_hz, ideal_mag, then magnitude, phase and group delay per curve); '-' = stdout")->capture_default_str()->check(file_path(true));
    cmd->add_option("--png", o->png, "write a Bode plot (magnitude and phase) to this PNG file")->check(file_path());
    cmd->add_flag("--db", o->db, "magnitude in dB instead of a logarithmic axis");
    cmd->callback([o] { run(*o); });
}

}  // namespace jacobid::cli
