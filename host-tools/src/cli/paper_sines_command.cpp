// SPDX-License-Identifier: MIT
// jacobid paper-sines: the reference paper's Section III experiment. Three sines with impulsive, white
// and 200 Hz noise; velocity and acceleration from the central Jacobi differentiator (kappa = mu = 12,
// q = 6, T = 0.21 s) and from a 6th-order 25 Hz forward-backward Butterworth + central Euler differences.
// Prints the RMS errors of both methods, writes Fig. 1 (errors) and Fig. 2 (Bode) as PNG.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>

#include "cli/command.hpp"
#include "options/kernel_options.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"
#include "jacobid/frequency_response.hpp"
#include "jacobid/kernel_design.hpp"
#include "plot/gnuplot.hpp"
#include "signal/differentiation.hpp"

namespace jacobid::cli {
namespace {

constexpr double kTwoPi = 6.283185307179586476925;
constexpr double kFrequencies[] = {4.0, 9.0, 15.0};
// The experiment is 2 s long; a million samples (1000 s at 1 kHz) already takes about 340 MB (the signal,
// four estimates and the plotted error series), so more is a typo.
constexpr double kMaxSamples = 1e6;
constexpr double kBytesPerSample = 340.0;

struct PaperSinesOptions {
    double duration = 2.0;
    double ts = 1e-3;
    unsigned seed = 1;
    double kappa = 12, mu = 12;
    int q = 6;
    double window = 0.21;
    std::string discretization = "trapezoidal";
    int bw_order = 6;
    double bw_cutoff = 25.0;
    std::string out_dir = "paper-sines";
    std::string format = "text";
};

struct MethodResult {
    std::string name;
    std::array<signal::Estimate, 2> estimates;  // velocity, acceleration
    std::array<double, 2> rms{};
};

double truth(int order, double t) {
    double v = 0;
    for (double f : kFrequencies) {
        const double w = kTwoPi * f;
        v += order == 1 ? w * std::cos(w * t) : -w * w * std::sin(w * t);
    }
    return v;
}

void run(const PaperSinesOptions& o) {
    refuse_oversized(fmt::format("--duration {:g} s at --ts {:g} s", o.duration, o.ts), std::round(o.duration / o.ts) + 1.0, kMaxSamples,
                     "samples", kBytesPerSample, "lower --duration or raise --ts");
    prepare_output_directory({"--out-dir", o.out_dir});
    const auto n = static_cast<std::size_t>(std::llround(o.duration / o.ts)) + 1;
    // Signal and noise (docs/method.md, "Paper Section III"): 0.2 N(0,1) + 0.2 sin(2 pi 200 t) + 0.2 Poisson(0.1).
    std::mt19937_64 rng(o.seed);
    std::normal_distribution<double> gaussian(0.0, 1.0);
    std::poisson_distribution<int> poisson(0.1);
    std::vector<double> t(n), x(n);
    for (std::size_t i = 0; i < n; ++i) {
        t[i] = static_cast<double>(i) * o.ts;
        double clean = 0;
        for (double f : kFrequencies) clean += std::sin(kTwoPi * f * t[i]);
        const double noise = 0.2 * gaussian(rng) + 0.2 * std::sin(kTwoPi * 200.0 * t[i]) + 0.2 * poisson(rng);
        x[i] = clean + noise;
    }

    std::vector<MethodResult> methods(2);
    methods[0].name = fmt::format("Jacobi (kappa=mu={:g}, q={}, T={:g} s)", o.kappa, o.q, o.window);
    methods[1].name = fmt::format("Butterworth {} {:g} Hz + Euler", o.bw_order, o.bw_cutoff);
    const signal::ButterworthSos sos = signal::design_butterworth_or_throw(o.bw_order, o.bw_cutoff, o.ts, "--bw-order/--bw-cutoff");
    std::array<std::vector<double>, 2> jacobi_weights;
    for (int d = 0; d < 2; ++d) {
        KernelOptions k;
        k.order = d + 1;
        k.kappa = o.kappa;
        k.mu = o.mu;
        k.q = o.q;
        k.window = o.window;
        k.ts = o.ts;
        k.discretization = o.discretization;
        const KernelParams p = to_kernel_params(k);
        jacobi_weights[d] = design_kernel_or_throw(p);
        methods[0].estimates[d] = signal::jacobi_estimate(p, jacobi_weights[d], x, "paper-sines signal");
        // Both methods are compared on the common interior (below), which the Jacobi half windows set;
        // the Butterworth filter runs over the whole record with scipy's odd padding at the ends.
        methods[1].estimates[d] = signal::butterworth_euler_estimate(sos, d + 1, o.ts, x, 0, "paper-sines signal");
    }
    // Common interior: where every estimate exists.
    double first = 0, last = static_cast<double>(n - 1);
    for (const auto& m : methods) {
        for (const auto& e : m.estimates) {
            first = std::max(first, e.first_index);
            last = std::min(last, e.first_index + static_cast<double>(e.values.size()) - 1);
        }
    }
    std::array<plot::Panel, 2> panels{plot::Panel{"Velocity error", "t [s]", "error [rad/s]", false, false, {}, ""},
                                      plot::Panel{"Acceleration error", "t [s]", "error [rad/s^2]", false, false, {}, ""}};
    for (std::size_t m = 0; m < methods.size(); ++m) {
        for (int d = 0; d < 2; ++d) {
            const signal::Estimate& e = methods[m].estimates[d];
            plot::Series s{methods[m].name, {}, {}, fmt::format("lines lw 1 lc {}", m + 1)};
            double sum = 0;
            std::size_t count = 0;
            for (double index = first; index <= last + 1e-9; index += 1.0) {
                const double ti = index * o.ts;
                const double err = e.values[static_cast<std::size_t>(std::llround(index - e.first_index))] - truth(d + 1, ti);
                sum += err * err;
                ++count;
                s.x.push_back(ti);
                s.y.push_back(err);
            }
            methods[m].rms[d] = std::sqrt(sum / static_cast<double>(count));
            panels[d].series.push_back(std::move(s));
        }
    }
    const std::string errors_png = (std::filesystem::path(o.out_dir) / "paper_sines_errors.png").string();
    const std::string bode_png = (std::filesystem::path(o.out_dir) / "paper_sines_bode.png").string();
    plot::render_png(errors_png, {panels[0], panels[1]});

    // Fig. 2: magnitude of both methods against the ideal, velocity and acceleration.
    std::vector<plot::Panel> bode;
    signal::ButterworthEuler bw{o.bw_order, o.bw_cutoff, sos};
    for (int d = 0; d < 2; ++d) {
        plot::Panel p{fmt::format("Magnitude, derivative order {}", d + 1), "frequency [Hz]", "|H|", false, true, {}, "set xrange [0:100]\n"};
        plot::Series ideal{"ideal", {}, {}, "lines dt 2 lw 2 lc rgb 'black'"}, jac{methods[0].name, {}, {}, "lines lw 1.5 lc 1"},
            but{methods[1].name, {}, {}, "lines lw 1.5 lc 2"};
        for (double f = 0.05; f <= 100.0; f += 0.05) {
            ideal.x.push_back(f);
            ideal.y.push_back(ideal_magnitude(d + 1, f));
            jac.x.push_back(f);
            jac.y.push_back(fir_response(Span<const double>(jacobi_weights[d]), o.ts, f).magnitude);
            but.x.push_back(f);
            but.y.push_back(std::abs(signal::butterworth_euler_response(bw, d + 1, o.ts, f)));
        }
        p.series = {ideal, jac, but};
        bode.push_back(std::move(p));
    }
    plot::render_png(bode_png, bode);

    const double ratio = methods[0].rms[1] / methods[1].rms[1];
    if (o.format == "json") {
        nlohmann::json j;
        for (const auto& m : methods) j["methods"].push_back({{"name", m.name}, {"velocity_rms_error", m.rms[0]}, {"acceleration_rms_error", m.rms[1]}});
        j["acceleration_rms_ratio_jacobi_over_butterworth"] = ratio;
        j["samples_compared"] = static_cast<std::size_t>(std::llround(last - first)) + 1;
        j["plots"] = {errors_png, bode_png};
        write_output("-", j.dump(2) + "\n");
    } else {
        fmt::print("Paper Section III: x = sin(2pi4t) + sin(2pi9t) + sin(2pi15t), Ts = {} s, {} s, seed {}\n", o.ts, o.duration, o.seed);
        fmt::print("noise: 0.2 N(0,1) + 0.2 sin(2pi200t) + 0.2 Poisson(0.1); errors over {} common interior samples\n\n",
                   std::llround(last - first) + 1);
        fmt::print("{:<44} {:>18} {:>22}\n", "method", "velocity RMS error", "acceleration RMS error");
        for (const auto& m : methods) fmt::print("{:<44} {:>18.4f} {:>22.3f}\n", m.name, m.rms[0], m.rms[1]);
        fmt::print("\nJacobi / Butterworth acceleration RMS ratio: {:.3f}\nplots: {}, {}\n", ratio, errors_png, bode_png);
    }
}

}  // namespace

void add_paper_sines_command(CLI::App& app) {
    auto o = std::make_shared<PaperSinesOptions>();
    CLI::App* cmd = app.add_subcommand("paper-sines", "the paper's Section III experiment: Jacobi vs Butterworth + Euler on noisy sines");
    cmd->add_option("--duration", o->duration, "signal length in seconds")->check(positive_number())->capture_default_str();
    cmd->add_option("--ts", o->ts, "sample period in seconds")->check(positive_number())->capture_default_str();
    cmd->add_option("--seed", o->seed, "noise seed")->check(whole_number_in(0, 4294967295.0))->capture_default_str();
    cmd->add_option("--kappa", o->kappa, "Jacobi kappa")->check(finite_number())->capture_default_str();
    cmd->add_option("--mu", o->mu, "Jacobi mu")->check(finite_number())->capture_default_str();
    cmd->add_option("--q", o->q, "Jacobi truncation order")->check(whole_number_from(0))->capture_default_str();
    cmd->add_option("--window,-T", o->window, "Jacobi window in seconds")->check(positive_number())->capture_default_str();
    cmd->add_option("--discretization", o->discretization, "trapezoidal or exact")->check(CLI::IsMember({"trapezoidal", "exact"}))->capture_default_str();
    cmd->add_option("--bw-order", o->bw_order, "Butterworth order")->check(whole_number_from(1))->capture_default_str();
    cmd->add_option("--bw-cutoff", o->bw_cutoff, "Butterworth cutoff in Hz")->check(positive_number())->capture_default_str();
    cmd->add_option("--out-dir", o->out_dir, "folder for the PNG plots")->capture_default_str()->check(file_path());
    cmd->add_option("--format", o->format, "text or json")->check(CLI::IsMember({"text", "json"}))->capture_default_str();
    cmd->callback([o] { run(*o); });
}

}  // namespace jacobid::cli
