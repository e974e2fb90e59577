// SPDX-License-Identifier: MIT
#include "jacobid/fwconfig/firmware_config.hpp"

#include "jacobid/differentiator_bank.hpp"

namespace jacobid::firmware {

KernelParams kernel_params(const EstimatorConfig& e, double sample_period, int channel) noexcept {
    KernelParams p;
    p.order = channel;
    p.kappa = e.kappa;
    p.mu = e.mu;
    p.q = e.q;
    p.window = channel == kPosition ? e.position_window : channel == kVelocity ? e.velocity_window : e.acceleration_window;
    p.sample_period = sample_period;
    p.xi = e.xi;
    p.discretization = e.discretization;
    return p;
}

}  // namespace jacobid::firmware
