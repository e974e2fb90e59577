// SPDX-License-Identifier: MIT
#include "options/kernel_description.hpp"

#include "jacobid/frequency_response.hpp"
#include "jacobid/kernel_design.hpp"

namespace jacobid::options {

nlohmann::json describe_kernel(const KernelParams& p, const std::vector<double>& w) {
    const Cutoff cutoff = find_cutoff(Span<const double>(w), p.sample_period, p.order);
    nlohmann::json j;
    j["parameters"] = {{"order", p.order},
                       {"kappa", p.kappa},
                       {"mu", p.mu},
                       {"q", p.q},
                       {"window", p.window},
                       {"ts", p.sample_period},
                       {"xi", p.xi},
                       {"discretization", p.discretization == Discretization::Exact ? "exact" : "trapezoidal"}};
    j["taps"] = w.size();
    j["effective_window"] = static_cast<double>(w.size() - 1) * p.sample_period;
    j["delay_samples"] = delay_samples(p);
    j["delay_seconds"] = delay_samples(p) * p.sample_period;
    j["cutoff_hz"] = cutoff.found ? nlohmann::json(cutoff.frequency) : nlohmann::json(nullptr);
    j["weights_order"] = "oldest sample first";
    j["weights"] = w;
    return j;
}

}  // namespace jacobid::options
