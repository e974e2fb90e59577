// SPDX-License-Identifier: MIT
#pragma once
// A torque-limited design of the PUMA 560, shared by the excite tests and bench_excite: the coefficients that
//   jacobid excite --robot examples/robots/puma560.yaml --duration 40 --velocity-limit 8.8,4.5,5,7.7,5.5,9.3
//     --acceleration-limit 36,18,25,37,27,39 --torque-noise 0.5,0.5,0.3,0.05,0.05,0.05
//     --torque-limit 232,233,63,10.7,7.2,9.8 --max-evaluations 300 --threads 1 --seed 1
// wrote (7 harmonics of 0.1 Hz, d-optimal, -log det -1017.85; its torques use 0.99, 0.92, 0.99, 0.54, 0.72, 0.70
// of their limits), with those limits, the description's position limits and the design's pose. An optimizer's
// iterates look like this: torques at their limits at a few peaks, where a random motion under a loose limit
// weighs every sample alike in the torque constraints' KS aggregates.
#include <Eigen/Core>
#include <vector>

#include "excite/excitation_problem.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::test {

// The design's limits: the command's, and the description's position limits.
inline std::vector<excite::JointLimits> puma560_torque_limited_limits(const robot::RobotDescription& robot) {
    const double velocity[] = {8.8, 4.5, 5, 7.7, 5.5, 9.3}, acceleration[] = {36, 18, 25, 37, 27, 39}, torque[] = {232, 233, 63, 10.7, 7.2, 9.8};
    std::vector<excite::JointLimits> limits(6);
    for (std::size_t j = 0; j < 6; ++j) limits[j] = {robot.joints[j].lower_limit, robot.joints[j].upper_limit, velocity[j], acceleration[j], torque[j]};
    return limits;
}

// The design's problem at 400 samples per period; `settings`' criterion and information model are the caller's
// (the design's noise and prior scales do not change where its torques peak).
inline excite::ExcitationProblem puma560_torque_limited_problem(const robot::RobotDescription& robot, const robot::RobotModel& model,
                                                                 const Eigen::VectorXd& parameters, excite::ProblemSettings settings) {
    Eigen::VectorXd pose(6);
    pose << 0.0, -0.95, 0.95, 0.0, 0.0, 0.0;
    settings.samples = 400;
    return excite::ExcitationProblem(model, parameters, excite::FourierBasis(10.0, 7, 0.1), pose, puma560_torque_limited_limits(robot), settings);
}

// The design's coefficients: joint j's (a_1, b_1, .., a_7, b_7), joint 0's first.
inline Eigen::VectorXd puma560_torque_limited_design() {
    Eigen::VectorXd c(6 * 14);
    c <<
        0.051144999914509673, 0.12217034753075441, -0.13403247910273244, -0.083818449028439213, -0.73091931643228758, -0.04994520780115988, -1.3335986770396335,
        0.40192292599383411, -1.7683243268384292, -0.11153767956250271, -2.6552180052834449, -0.39974003303378025, 6.3820109828694767, 0.26494654154689146,
        -0.093177922356163637, -0.090971239673619503, -0.08795391027217439, 0.24278798271260443, -0.37652538022659293, -0.23120958486705306, -0.40525313217947695,
        0.25653775942398305, -1.2888717860129097, 0.016970231063359154, -1.2499812092001288, 0.30329433181810628, 3.0441825837955361, -0.35874363577932833,
        -0.06193199336856936, 0.038176241323240517, -0.19413262521884236, 0.22247759835845313, -0.86911747054867494, -0.16849531270995804, -0.74302986355725875,
        0.10674446881775239, -0.86693947462549226, 0.13656760162954354, -0.88709028179833671, 0.021481214430496845, 3.5410174571706059, -0.15578382640561819,
        -0.2478369300498009, -0.025105528144437551, 0.031460329072469678, 0.14757502298063474, 0.25889344159616828, -0.053577902574521025, 0.52988497356154673,
        0.19784726594182728, 0.29552011976453085, 1.3867479636417466, 1.9879919457545823, -0.54278601380510172, -1.9277532827108403, -0.56894698594543569,
        0.016097098976900415, -0.26162384309447406, -0.16688663608655652, 0.39643254862674265, 0.028235613010827963, 0.33991812697438245, -0.42967863082413743,
        0.087617270715010478, -0.027682324359236024, -0.44055691094506966, 3.140249962234221, 0.029986958398187363, -2.2064941035594332, -0.0032694565112665426,
        -0.014939449748188907, 0.21757762053900176, -0.25032816136737679, -0.62834921853998382, 0.36432604456035639, -0.1274456061885243, 0.36618494256127621,
        0.0062575700138971764, -3.6079049962375866, 0.057177019480380856, -0.81831228529576194, -0.018997967698043537, 3.794786792661919, 0.14010030625985265;
    return c;
}

}  // namespace jacobid::test
