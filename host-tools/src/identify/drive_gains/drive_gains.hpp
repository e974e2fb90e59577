// SPDX-License-Identifier: MIT
#pragma once
// Drive gains from a known payload (identify --drive-gains; global identification, Gautier and Briot 2014;
// docs/identify.md, "Drive gains"). Two logs of the robot, without and with a payload of
// known mass on the last link, go through the same pipeline (the unloaded log's torque delay, Coulomb
// smoothing, bandwidth, windows and decimation imposed on the loaded one); with y_j the logged effort of
// joint j (the log's torque column as loaded: currents, or currents times a log format's prior gains) and
// g_j its unknown gain, every decimated row of joint j is one equation
//     unloaded:  W_j theta                    - y_j g_j = 0
//     loaded:    W_j theta + W_j K_L phi_u    - y_j g_j = -W_j K_L phi_k
// theta the base parameters, K_L the regrouping's columns of the last link's ten standard parameters (a
// payload fixed to the last link adds its inertial parameters, about the last link's frame, to that link's),
// phi_u the payload parameters that are not given and phi_k the given ones (mass, and optionally centre of mass
// and inertia). The known mass fixes the scale of the gains. The stacked problem is solved by the project's
// least squares (OLS or WLS with their std), by a mixed LS-TLS (drive_gains_tls.hpp) and with the
// physical constraints (drive_gains_constrained.hpp).
#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "identify/identify_run.hpp"
#include "identify/report/report.hpp"
#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::robot {
class SerialRobotModel;
}

namespace jacobid::identify {

// What is known of the payload, in the last link's frame (for a URDF: the frame of the last moving joint).
struct PayloadKnowledge {
    double mass = 0.0;                      // kg, > 0
    std::optional<Eigen::Vector3d> com;     // m
    // About the centre of mass: XX XY XZ YY YZ ZZ (kg.m^2); needs `com`.
    std::optional<Eigen::Matrix<double, 6, 1>> inertia;
};

// The payload's ten standard parameters (XX XY XZ YY YZ ZZ MX MY MZ M about the link frame's origin) and which
// of them are known: the mass always, the first moments with `com`, the inertias with `com` and `inertia`.
struct PayloadParameters {
    Eigen::Matrix<double, 10, 1> known = Eigen::Matrix<double, 10, 1>::Zero();  // unknown entries 0
    std::vector<int> unknown;                                                    // indices 0..9
};
PayloadParameters payload_parameters(const PayloadKnowledge& payload);
// "XXL" .. "ML": the payload's parameter names in the order above.
const std::vector<std::string>& payload_names();

// One estimator's answer.
struct DriveGainEstimate {
    std::string estimator;       // "ols" | "wls", "tls", "constrained"
    Eigen::VectorXd gains;       // per joint, multiplying the log's effort column as loaded
    Eigen::VectorXd std_dev;     // per joint; NaN when the estimator gives none
    Eigen::Matrix<double, 10, 1> payload = Eigen::Matrix<double, 10, 1>::Constant(std::nan(""));  // XX..M; NaN: not identified
    bool converged = true;
    std::string note;            // e.g. the constrained solver's figures
};

struct DriveGainResult {
    MethodResult method;  // the least squares over [theta; phi_u; g]: names base..., payload XXL.., gains G1..
    PayloadParameters payload;
    int parameter_count = 0, payload_columns = 0, joints = 0;
    std::size_t unloaded_equations = 0, loaded_equations = 0;
    JointFactors factors;   // per joint, over [theta; phi_u; g | rhs]
    // Per joint, the payload's share of the loaded log's torque: ||W_j K_L phi|| / ||g_j y_j||, phi the known and
    // the least-squares payload parameters.
    std::vector<double> payload_share;
    std::vector<double> prior_gains;  // the log format's gains (1 without one): the absolute gain is prior x g
    DriveGainEstimate least_squares, tls;
    std::optional<DriveGainEstimate> constrained;
    std::string unloaded_source, loaded_source;
};

// The stacked rows through the pipeline and the least squares; InputError when the logs have different joint
// counts, the model has no standard parameters (mdh or urdf needed), the mass is not positive or inertia is
// given without a centre of mass, or the gains are not identifiable (a gain column dropped by the rank test).
DriveGainResult identify_drive_gains(const robot::RobotDescription& description, const robot::RobotModel& nominal, const LogColumns& unloaded,
                                     const LogColumns& loaded, const IdentifySettings& settings, const PayloadKnowledge& payload);

// Column of the last link's parameter `index` (0..9 in XX..M order) in the model's standard parameters.
std::vector<int> last_link_columns(const robot::SerialRobotModel& model);

}  // namespace jacobid::identify
