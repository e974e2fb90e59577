// SPDX-License-Identifier: MIT
#pragma once
// The sign function of Coulomb friction, exact or smoothed. Real drives show a continuous transition
// through zero velocity; if the data's friction is smooth (2/pi atan(alpha qd)) and the regressor uses
// sign(qd), the identified Coulomb levels come out ~25 % low (docs/method.md, "Pitfalls"), so the choice is a model
// option shared by the simulator and the regressor.
#include <cmath>

namespace jacobid::robot {

enum class CoulombModel {
    Sign,        // sign(qd), 0 at qd = 0
    SmoothAtan,  // 2/pi atan(alpha qd)
};

struct CoulombSign {
    CoulombModel model = CoulombModel::Sign;
    double alpha = 100.0;  // s/rad, slope factor of the smoothed sign (SmoothAtan only)

    double operator()(double velocity) const noexcept {
        if (model == CoulombModel::SmoothAtan) return 0.63661977236758134308 * std::atan(alpha * velocity);
        return velocity > 0.0 ? 1.0 : (velocity < 0.0 ? -1.0 : 0.0);
    }
    // d/d velocity of the above: 2/pi alpha / (1 + (alpha qd)^2) smoothed; 0 for sign(qd) (flat on either side).
    double slope(double velocity) const noexcept {
        if (model != CoulombModel::SmoothAtan) return 0.0;
        const double a = alpha * velocity;
        return 0.63661977236758134308 * alpha / (1.0 + a * a);
    }
};

}  // namespace jacobid::robot
