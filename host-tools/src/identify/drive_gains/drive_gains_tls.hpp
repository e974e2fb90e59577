// SPDX-License-Identifier: MIT
#pragma once
// The drive-gain problem (drive_gains.hpp) as a mixed LS-TLS problem (Van Huffel and Vandewalle 1991,
// ch. 3.6.3): the regressor columns (base and payload parameters) are taken as exact, the logged effort
// columns (one per gain) and the known payload's column as noisy. On the least squares' weighted triangular
// factor (rows scaled by the joints' weights, so every joint's noise is about one unit), QR of the columns
// [exact | gains | known payload] leaves a small block R22 over the noisy columns; the TLS solution is its
// smallest right singular vector, the exact part follows by back substitution. Each gain column is scaled
// by its least-squares gain first, so every noisy column is in N.m: the TLS then weighs an error of one
// N.m alike in every joint (without it, the answer would depend on the currents' units). No std is given.
#include "identify/drive_gains/drive_gains.hpp"

namespace jacobid::identify {

// estimator "tls"; gains and the payload's parameters (NaN where the least squares did not identify them).
DriveGainEstimate drive_gains_tls(const DriveGainResult& result);

}  // namespace jacobid::identify
