// SPDX-License-Identifier: MIT
#pragma once
// Stacking identification systems that were accumulated separately (the segments of a log split at its
// gaps; later, several logs at once): the equations of both are the rows of [R_total; R_part], whose QR
// factor R satisfies R^T R = R_total^T R_total + R_part^T R_part, i.e. exactly the factor of all the rows
// stacked, without ever holding the rows (running_qr.hpp, add_factor).
#include "identify/solve/least_squares.hpp"

namespace jacobid::identify {

// Folds `part` into `total`, joint by joint; an empty `total` becomes a copy of `part`. InputError when
// both hold factors and their joint counts or column counts differ (systems of different models).
void merge_factors(JointFactors& total, const JointFactors& part);

}  // namespace jacobid::identify
