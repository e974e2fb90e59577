// SPDX-License-Identifier: MIT
// The robot description's controller (robot/controller_description.hpp): both forms round-trip through
// to_yaml, malformed ones name the key; and the closed loop the estimators simulate along a log's reference
// (identify/solve/reference_simulation.hpp) reproduces the simulator's own true states when given the true
// parameters: the same loop, the same gains, the reference at the same control instants.
#include <gtest/gtest.h>

#include <string>

#include "core/errors.hpp"
#include "identify/plan/log_columns.hpp"
#include "identify/solve/reference_simulation.hpp"
#include "robot/robot_description.hpp"
#include "sim/simulator.hpp"

namespace jacobid {
namespace {

robot::RobotDescription parse(const std::string& controller) {
    return robot::parse_robot_description("model: planar2r\nfriction: {coulomb: smooth, alpha: 100}\ncontroller: " + controller + "\n", "r.yaml");
}

std::string error_of(const std::string& controller) {
    try {
        parse(controller);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(ControllerDescription, BothFormsRoundTripThroughToYaml) {
    for (const char* c : {"{kp: [900, 30.5], kd: [60, 2], rate: 500, substeps: 4}", "{omega: 25, damping: 0.7, rate: 1000}"}) {
        const auto d = parse(c);
        ASSERT_TRUE(d.controller) << c;
        const auto again = robot::parse_robot_description(robot::to_yaml(d), "again.yaml");
        ASSERT_TRUE(again.controller) << c;
        EXPECT_EQ(again.controller->kp, d.controller->kp) << c;
        EXPECT_EQ(again.controller->kd, d.controller->kd) << c;
        EXPECT_EQ(again.controller->omega, d.controller->omega) << c;
        EXPECT_EQ(again.controller->damping, d.controller->damping) << c;
        EXPECT_EQ(again.controller->rate, d.controller->rate) << c;
        EXPECT_EQ(again.controller->substeps, d.controller->substeps) << c;
    }
    EXPECT_EQ(parse("{kp: [900, 30.5], kd: [60, 2]}").controller->kp, (std::vector<double>{900, 30.5}));
    EXPECT_FALSE(robot::parse_robot_description("model: planar2r\n", "r.yaml").controller);
    EXPECT_EQ(robot::to_yaml(robot::parse_robot_description("model: planar2r\n", "r.yaml")).find("controller"), std::string::npos);
}

TEST(ControllerDescription, MalformedOnesNameTheKey) {
    const std::pair<const char*, const char*> cases[] = {
        {"{omega: 30, gain: 2}", "controller.gain: unknown key"},
        {"{kp: [1, 2, 3], kd: [1, 2]}", "controller.kp"},
        {"{kp: [1, 2]}", "controller.kd: missing"},
        {"{kp: [1, 2], kd: [1, 2], omega: 3}", "controller.omega"},
        {"{rate: 1000}", "controller.omega: missing"},
        {"{omega: -3}", "controller.omega"},
        {"{kp: [1, -2], kd: [1, 2]}", "must be >= 0"},
        {"[1, 2]", "controller"},
    };
    for (const auto& [controller, expected] : cases) {
        const std::string error = error_of(controller);
        EXPECT_NE(error.find(expected), std::string::npos) << controller << ": " << error;
    }
}

TEST(ReferenceSimulation, TrueParametersReproduceTheSimulatorsStates) {
    const auto d = parse("{omega: 30, damping: 1, rate: 1000}");
    const auto model = robot::make_robot_model(d);
    const Eigen::VectorXd x = robot::true_parameters(d, *model);
    sim::SimulationSettings settings;
    settings.duration = 3.0;
    settings.omega_dyn = 30.0;
    std::vector<std::vector<double>> q(2), qd(2), qdd(2);
    sim::MeasurementSettings sensors;
    sensors.encoder_counts_per_rev = 0.0;
    sim::MeasurementModel measurement(sensors);
    sim::MeasuredLog log;
    log.sample_period = 1e-3;
    log.q.resize(2);
    log.tau.resize(2);
    log.q_ref.resize(2);
    log.qd_ref.resize(2);
    sim::simulate(*model, x, d.joints, settings, measurement, [&](const sim::SimulatedSample& s) {
        for (int j = 0; j < 2; ++j) {
            q[j].push_back(s.q[j]);
            qd[j].push_back(s.qd[j]);
            qdd[j].push_back(s.qdd[j]);
            log.q[j].push_back(s.q_measured[j]);
            log.tau[j].push_back(s.tau_measured[j]);
            log.q_ref[j].push_back(s.q_ref[j]);
            log.qd_ref[j].push_back(s.qd_ref[j]);
        }
    });
    identify::LogColumns columns = identify::log_columns(log.q, log.tau, log.sample_period, "sim");
    for (std::size_t j = 0; j < 2; ++j) {
        columns.q_ref.push_back(&log.q_ref[j]);
        columns.qd_ref.push_back(&log.qd_ref[j]);
    }
    identify::require_reference_simulation(columns, d, "didim");
    identify::PipelineInfo info;
    info.first = 0;
    info.last = columns.samples();
    const identify::StateEstimates e = identify::simulate_along_reference(*model, x, d, *model, columns, info);
    double worst_q = 0.0, worst_qdd = 0.0;
    for (std::size_t j = 0; j < 2; ++j) {
        EXPECT_EQ(e.tau[j], log.tau[j]);  // the log's own torque, unfiltered
        for (std::size_t k = 0; k < q[j].size(); ++k) {
            worst_q = std::max(worst_q, std::abs(e.q[j][k] - q[j][k]));
            worst_qdd = std::max(worst_qdd, std::abs(e.qdd[j][k] - qdd[j][k]));
        }
    }
    EXPECT_LT(worst_q, 1e-12);
    EXPECT_LT(worst_qdd, 1e-9);
    // Another X gives other states: the simulation does depend on the parameters it is given.
    Eigen::VectorXd heavier = x;
    heavier[0] *= 1.1;
    const identify::StateEstimates other = identify::simulate_along_reference(*model, heavier, d, *model, columns, info);
    double moved = 0.0;
    for (std::size_t k = 0; k < q[0].size(); ++k) moved = std::max(moved, std::abs(other.q[0][k] - q[0][k]));
    EXPECT_GT(moved, 1e-4);
}

}  // namespace
}  // namespace jacobid
