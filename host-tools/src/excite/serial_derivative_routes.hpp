// SPDX-License-Identifier: MIT
#pragma once
// The two routes of RegressorDerivatives that only serial robots take (regressor_derivatives.hpp), each in its own
// translation unit: the adjoint is instantiated once per joint count (the library's fixed-size Newton-Euler
// regressor), and compiling every count of both routes in one file made it the longest job of the `jacobid` build.
#include <memory>

#include "excite/regressor_derivatives.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::excite {

// The adjoint of the Newton-Euler regressor (regressor_derivatives_adjoint.cpp).
std::unique_ptr<RegressorDerivatives> make_adjoint_derivatives(const robot::SerialRobotModel& model);
// Forward-mode automatic differentiation (regressor_derivatives_automatic.cpp).
std::unique_ptr<RegressorDerivatives> make_automatic_derivatives(const robot::SerialRobotModel& model);

}  // namespace jacobid::excite
