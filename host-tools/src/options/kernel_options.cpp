// SPDX-License-Identifier: MIT
#include "options/kernel_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>
#include <type_traits>

#include "core/errors.hpp"
#include "options/option_checks.hpp"
#include "jacobid/kernel_design.hpp"
#include "signal/kernel_design_checked.hpp"

namespace jacobid::options {

namespace {
// Host-side bound on kernel length: 10 million taps is far beyond any useful window and keeps a typo
// (--window 1000) from allocating gigabytes.
constexpr std::size_t kMaxHostTaps = 10'000'000;
}  // namespace

void add_kernel_options(CLI::App* command, KernelOptions& o, bool with_order, bool with_ts) {
    // The ranges of kappa, mu and q + n are the library's (validate()); the validators refuse what is no number.
    if (with_order) {
        command->add_option("--order,-n", o.order, "derivative order n (0, 1, 2 or 3)")->check(whole_number_in(0, kMaxOrder))->capture_default_str();
    }
    command->add_option("--kappa", o.kappa, "Jacobi weight exponent kappa in (-1, 300] of (1 + tau), the oldest end")
        ->check(finite_number())
        ->capture_default_str();
    command->add_option("--mu", o.mu, "Jacobi weight exponent mu in (-1, 300] of (1 - tau), the newest end")->check(finite_number())->capture_default_str();
    command->add_option("--q", o.q, "truncation order q >= 0 (polynomial degree q + n)")->check(whole_number_from(0))->capture_default_str();
    command->add_option("--window,-T", o.window, "window length T in seconds (taps = round(T/Ts) + 1)")->check(positive_number());
    if (with_ts) command->add_option("--ts", o.ts, "sample period Ts in seconds")->check(positive_number())->required();
    command->add_option("--xi", o.xi,
                        "evaluation point in [-1, 1]: 0 or 'central' (delay T/2), 1 or 'causal' (no delay), "
                        "'delayed' (largest root of P_{q+1}^{(mu+n,kappa+n)}), or any number")
        ->capture_default_str();
    command->add_option("--discretization", o.discretization, "trapezoidal (as the paper) or exact (polynomial-exact on the grid)")
        ->check(CLI::IsMember({"trapezoidal", "exact"}))
        ->capture_default_str();
}

std::string option_for(KernelStatus status, const KernelSource& source) {
    if (!source.overrides.empty()) return source.overrides;
    switch (status) {
        case KernelStatus::InvalidOrder: return "--order";
        case KernelStatus::InvalidKappa: return "--kappa";
        case KernelStatus::InvalidMu: return "--mu";
        case KernelStatus::InvalidTruncation: return "--q";
        case KernelStatus::InvalidSamplePeriod: return source.sample_period;
        case KernelStatus::WindowTooShort:
        case KernelStatus::TooManyTaps:
        case KernelStatus::TooFewPoints: return "--window";
        case KernelStatus::InvalidXi:
        case KernelStatus::ClosedFormNeedsCentral: return "--xi";
        case KernelStatus::Ok: break;
    }
    return "kernel parameters";
}

KernelParams to_kernel_params(const KernelOptions& o, const KernelSource& source) {
    KernelParams p;
    p.order = o.order;
    p.kappa = o.kappa;
    p.mu = o.mu;
    p.q = o.q;
    p.window = o.window;
    p.sample_period = o.ts;
    p.discretization = o.discretization == "exact" ? Discretization::Exact : Discretization::Trapezoidal;
    if (o.xi == "central") {
        p.xi = 0.0;
    } else if (o.xi == "causal") {
        p.xi = 1.0;
    } else if (o.xi == "delayed") {
        if (p.order < 0 || p.order > kMaxOrder || p.q < 0) {
            p.xi = 0.0;  // validation below reports the real problem
        } else {
            p.xi = delayed_causal_xi(p.order, p.kappa, p.mu, p.q);
        }
    } else {
        try {
            std::size_t used = 0;
            p.xi = std::stod(o.xi, &used);
            if (used != o.xi.size()) throw std::invalid_argument(o.xi);
        } catch (const std::exception&) {
            throw InputError(fmt::format("{}: expected a number in [-1, 1] or central|causal|delayed, got '{}'",
                                         source.overrides.empty() ? "--xi" : source.overrides, o.xi));
        }
    }
    const std::string window = source.overrides.empty() ? "--window" : source.overrides;
    if (!(o.window > 0.0)) throw InputError(fmt::format("{}: the window length T in seconds is required and must be > 0", window));
    const KernelStatus s = validate(p, kMaxHostTaps);
    if (s != KernelStatus::Ok) throw InputError(fmt::format("{}: {}", option_for(s, source), describe(s)));
    if (check_weighted_points(p) == KernelStatus::TooFewPoints) {
        throw InputError(fmt::format("{}: a window of {} taps has {} weighted samples, fewer than the q + order + 1 = {} coefficients of "
                                     "the polynomial; lengthen the window or lower --q",
                                     window, tap_count(p), weighted_point_count(p), p.q + p.order + 1));
    }
    return p;
}

KernelOptions with_overrides(KernelOptions o, const std::string& spec, const std::string& option_name) {
    std::size_t start = 0;
    while (start <= spec.size()) {
        std::size_t comma = spec.find(',', start);
        if (comma == std::string::npos) comma = spec.size();
        const std::string item = spec.substr(start, comma - start);
        start = comma + 1;
        if (item.empty()) continue;
        const std::size_t eq = item.find('=');
        if (eq == std::string::npos) throw InputError(fmt::format("{} '{}': expected key=value, got '{}'", option_name, spec, item));
        const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
        auto number = [&](auto& target) {
            try {
                std::size_t used = 0;
                const double v = std::stod(value, &used);
                if (used != value.size() || !std::isfinite(v)) throw std::invalid_argument(value);
                target = static_cast<std::remove_reference_t<decltype(target)>>(v);
            } catch (const std::exception&) {
                throw InputError(fmt::format("{} '{}': {} expects a finite number, got '{}'", option_name, spec, key, value));
            }
        };
        if (key == "order" || key == "n") number(o.order);
        else if (key == "kappa") number(o.kappa);
        else if (key == "mu") number(o.mu);
        else if (key == "q") number(o.q);
        else if (key == "window" || key == "T") number(o.window);
        else if (key == "ts") number(o.ts);
        else if (key == "xi") o.xi = value;
        else if (key == "discretization") {
            if (value != "trapezoidal" && value != "exact") throw InputError(fmt::format("{} '{}': discretization must be trapezoidal or exact", option_name, spec));
            o.discretization = value;
        } else {
            throw InputError(fmt::format("{} '{}': unknown key '{}' (order, kappa, mu, q, window, ts, xi, discretization)", option_name, spec, key));
        }
    }
    return o;
}

std::string kernel_label(const KernelParams& p) {
    std::string label = fmt::format("n{} k{:g} m{:g} q{} T{:g}", p.order, p.kappa, p.mu, p.q, p.window);
    if (p.xi != 0.0) label += fmt::format(" xi{:.3g}", p.xi);
    if (p.discretization == Discretization::Exact) label += " exact";
    return label;
}

std::vector<double> design_kernel_or_throw(const KernelParams& params) {
    return signal::design_kernel_or_throw(params, [](KernelStatus s) { return option_for(s); });
}

}  // namespace jacobid::options
