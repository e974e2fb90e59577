// SPDX-License-Identifier: MIT
#pragma once
// The low-pass that a central Jacobi velocity kernel applies to the velocity, as a kernel for the torque
// (docs/method.md, "Pitfalls": same filter on both sides). A Jacobi estimate is a low-pass filtered
// derivative, qd^ = G * qd with |G| < 1 already inside F_p's band (1.8 % at F_p for the default cutoffs),
// while the raw torque is not filtered: F_p then keeps a band in which the regressor and Y differ, and the
// difference projects onto the friction columns (FC1 -0.4 %, FV1 +0.2 % on noise-free simulations).
//
// Summation by parts gives G exactly: with c_k the velocity weights (oldest first, sum c_k = 0),
//   sum_k c_k x_k = sum_k g_k (x_{k+1} - x_k) / Ts,   g_k = -Ts sum_{i<=k} c_i,
// so qd^ is the FIR g (sum g_k = 1) applied to the first differences, i.e. to the velocity at half
// samples. The torque at half samples is (tau_k + tau_{k+1}) / 2 (an error of (w Ts)^2 / 12 against the
// difference quotient, 1.6e-4 at 7 Hz and 1 kHz), hence the torque kernel s_k = (g_{k-1} + g_k) / 2:
// the same length and centre as the velocity kernel, symmetric, sum 1.
#include <vector>

namespace jacobid::identify {

// The torque kernel s (oldest sample first, same length as `velocity_weights`) of a central velocity
// kernel with sample period `ts`.
std::vector<double> torque_smoothing_kernel(const std::vector<double>& velocity_weights, double ts);

}  // namespace jacobid::identify
