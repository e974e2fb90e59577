// SPDX-License-Identifier: MIT
#pragma once
// The derivatives excite's gradients need at one sample, in the 3n coordinates z = (q, qd, qdd):
//   - dphi/dz of phi = <H, Y(q, qd, qdd)> (H: joints x base parameters, the criterion's dF/dW at that sample);
//   - dtau/dz of tau = Y(q, qd, qdd) x (the model's torque: the torque limits).
// Three routes, one interface:
//  - the adjoint of the Newton-Euler regressor (lib/include/jacobid/robot/rnea_regressor_adjoint.hpp), serial
//    robots only: one forward pass and one adjoint pass per sample give dphi/dz exactly, and one more adjoint
//    pass with a lane per joint dtau/dz; the default, because it is the fastest (docs/excite.md, "Speed");
//  - central differences of the model's regressor (step 1e-6 in q and qd, exact in qdd where Y is linear),
//    5n + 1 regressor calls per sample: any model (the route every other model takes);
//  - forward-mode automatic differentiation (Eigen's AutoDiffScalar, 3n derivative lanes in a fixed capacity) of a
//    Newton-Euler regressor written again here with a template scalar (link kinematics, the 6 x 10 wrench
//    matrices, their projections on the carrying joints; friction and rotor inertia by hand), serial robots
//    only: exact, and an independent check of the others, but the slowest (every derivative lane rides along
//    through every operation, including the many whose derivative is zero).
#include <Eigen/Core>
#include <memory>

#include "robot/robot_model.hpp"

namespace jacobid::excite {

enum class DerivativeRoute { Adjoint, CentralDifferences, Automatic };
const char* to_string(DerivativeRoute route);

class RegressorDerivatives {
public:
    virtual ~RegressorDerivatives() = default;
    // H (joints x parameters) may be empty: dphi is then not computed. x: the model's parameters.
    // dphi: 3n; dtau (not computed when null): joints x 3n. Does not keep state between calls (const, may run on several threads).
    virtual void evaluate(const double* q, const double* qd, const double* qdd, const Eigen::Ref<const Eigen::MatrixXd>& H, const Eigen::VectorXd& x,
                          Eigen::VectorXd& dphi, Eigen::MatrixXd* dtau) const = 0;
    // The route this is (central differences when the one asked for does not apply to the model).
    virtual DerivativeRoute route() const = 0;
};

// `route` for a SerialRobotModel; central differences for any other model.
std::unique_ptr<RegressorDerivatives> make_regressor_derivatives(const robot::RobotModel& model, DerivativeRoute route = DerivativeRoute::Adjoint);

}  // namespace jacobid::excite
