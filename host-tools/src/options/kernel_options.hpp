// SPDX-License-Identifier: MIT
#pragma once
// Command-line options that describe one Jacobi kernel, shared by kernel, bode and differentiate.
#include <string>
#include <vector>

#include "jacobid/kernel_params.hpp"

namespace CLI {
class App;
class Option;
}

namespace jacobid::options {

struct KernelOptions {
    int order = 1;
    double kappa = 6.0;
    double mu = 6.0;
    int q = 2;
    double window = 0.0;     // seconds; 0 = not given
    double ts = 0.0;         // seconds; 0 = not given (commands reading a log take it from the time column)
    std::string xi = "0";    // a number in [-1, 1], or central | causal | delayed
    std::string discretization = "trapezoidal";
};

// Adds --kappa --mu --q --window --xi --discretization (and --order, --ts when asked) to `command`.
void add_kernel_options(CLI::App* command, KernelOptions& options, bool with_order, bool with_ts);

// Where the values of a KernelOptions came from, for messages that must not name an option the user did not
// give: `overrides` (e.g. "--compare 'kappa=nan'") replaces every option name when set; `sample_period`
// names the source of Ts ("--ts", or a log's time column for commands that read one).
struct KernelSource {
    std::string overrides;
    std::string sample_period = "--ts";
};

// Converts and validates (including a window too short for the polynomial, any discretization); InputError
// names the offending option ("--kappa: kappa must be ...") or `source`.
KernelParams to_kernel_params(const KernelOptions& options, const KernelSource& source = {});

// The option (or source) a KernelStatus complains about, for messages.
std::string option_for(KernelStatus status, const KernelSource& source = {});

// Applies "key=value,key=value" overrides (keys: order kappa mu q window ts xi discretization) to
// `options`, e.g. "kappa=12,mu=12,q=6,window=0.21"; InputError names `option_name` and the bad item.
KernelOptions with_overrides(KernelOptions options, const std::string& spec, const std::string& option_name);

// Short label of a kernel for legends and CSV headers, e.g. "n1 k6 m6 q2 T0.2".
std::string kernel_label(const KernelParams& params);

// Designs the kernel (any length the machine can hold) or throws InputError naming the option.
std::vector<double> design_kernel_or_throw(const KernelParams& params);

}  // namespace jacobid::options
