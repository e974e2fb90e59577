// SPDX-License-Identifier: MIT
// The simulator's hidden effects checked against physics written independently here: the noise-free
// states (--states) give the true motor torque, and tau - D(q, qd, qdd) X_nominal must be exactly the
// injected effect (gravity: the gradient of the potential energy, by central differences); a torque delay
// must shift the logged torque by exactly the delay.
#include <gtest/gtest.h>

#include <cmath>

#include "diagnose_test_support.hpp"
#include "io/csv_table.hpp"
#include "jacobid/robot/planar2r.hpp"

namespace jacobid::test {
namespace {

constexpr double kG = 9.80665;
constexpr double kDeg = M_PI / 180.0;

struct States {
    io::CsvTable table;
    nlohmann::json truth;
};

States simulate_states(const std::string& name, const std::string& effects) {
    const std::string log = scratch(name + ".csv"), states = scratch(name + ".states.csv"), truth = scratch(name + ".truth.json");
    const auto r = simulate_log(log, 3, 5, "--states " + states + " --truth " + truth + " " + effects);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return {io::read_csv(states), read_json(truth)};
}

// tau - D X of the nominal 2R model with the truth's parameters, at sample k.
robot::Planar2R::Joints unexplained(const States& s, std::size_t k) {
    const robot::Planar2R model(robot::Planar2RConfig{0.5, {robot::CoulombModel::SmoothAtan, 100.0}, false, false});
    robot::Planar2R::Regressor D;
    model.regressor({s.table.column("q1")[k], s.table.column("q2")[k]}, {s.table.column("qd1")[k], s.table.column("qd2")[k]},
                    {s.table.column("qdd1")[k], s.table.column("qdd2")[k]}, D);
    Eigen::VectorXd x(model.parameter_count());
    for (int c = 0; c < model.parameter_count(); ++c) x[c] = s.truth["parameters"][model.parameter_name(c)].get<double>();
    const Eigen::Vector2d tau = D.leftCols(model.parameter_count()) * x;
    return {s.table.column("tau1")[k] - tau[0], s.table.column("tau2")[k] - tau[1]};
}

template <class Expected>
void expect_everywhere(const States& s, Expected expected, double tolerance) {
    const std::size_t n = s.table.column("t").size();
    ASSERT_GT(n, 1000u);
    for (std::size_t k = 0; k < n; k += 7) {
        const auto got = unexplained(s, k);
        const auto want = expected(k);
        ASSERT_NEAR(got[0], want[0], tolerance) << "joint 1, sample " << k;
        ASSERT_NEAR(got[1], want[1], tolerance) << "joint 2, sample " << k;
    }
}

double smooth_sign(double v) { return 2.0 / M_PI * std::atan(100.0 * v); }

TEST(EffectInjection, NoEffectLeavesNothingUnexplained) {
    const States s = simulate_states("none", "");
    EXPECT_TRUE(s.truth["effects"].empty());
    expect_everywhere(s, [](std::size_t) { return robot::Planar2R::Joints(0.0, 0.0); }, 1e-9);
}

TEST(EffectInjection, FrictionTermsAreExactlyTheirFormulas) {
    const States s = simulate_states("friction", "--effect coulomb_offset:joint=1,value=0.2 --effect coulomb_asymmetry:joint=2,value=0.03 "
                                                 "--effect stribeck:joint=1,value=0.3,velocity=0.09 --effect viscous_nonlinear:joint=2,value=0.01");
    ASSERT_EQ(s.truth["effects"].size(), 4u);
    EXPECT_EQ(s.truth["effects"][2]["name"], "stribeck");
    EXPECT_EQ(s.truth["effects"][2]["velocity"], 0.09);
    const auto& qd1 = s.table.column("qd1");
    const auto& qd2 = s.table.column("qd2");
    expect_everywhere(s, [&](std::size_t k) {
        const double v1 = qd1[k], v2 = qd2[k];
        return robot::Planar2R::Joints(0.2 + 0.3 * smooth_sign(v1) * std::exp(-(v1 / 0.09) * (v1 / 0.09)),
                                       0.03 * std::abs(smooth_sign(v2)) + 0.01 * v2 * std::abs(v2));
    }, 1e-9);
}

TEST(EffectInjection, CoggingAndRotorInertia) {
    const States s = simulate_states("cogging", "--effect cogging:joint=2,amplitude=0.15,order=6,phase=40 --effect rotor_inertia:joint=2,value=0.05");
    const auto& q2 = s.table.column("q2");
    const auto& qdd2 = s.table.column("qdd2");
    expect_everywhere(s, [&](std::size_t k) { return robot::Planar2R::Joints(0.0, 0.15 * std::sin(6.0 * q2[k] + 40.0 * kDeg) + 0.05 * qdd2[k]); }, 1e-9);
}

TEST(EffectInjection, GravityIsTheGradientOfThePotentialOfATiltedBase) {
    const States s = simulate_states("gravity", "--effect gravity:tilt=3,direction=30,mx1=1.5");
    const double mx2 = s.truth["parameters"]["MX2"].get<double>(), my2 = s.truth["parameters"]["MY2"].get<double>();
    const double gp = kG * std::sin(3.0 * kDeg);
    const double gx = gp * std::cos(30.0 * kDeg), gy = gp * std::sin(30.0 * kDeg);
    // Potential energy: -g . (sum of the links' first moments in the base frame).
    auto potential = [&](double q1, double q2) {
        const double mx = 1.5 * std::cos(q1) + mx2 * std::cos(q1 + q2) - my2 * std::sin(q1 + q2);
        const double my = 1.5 * std::sin(q1) + mx2 * std::sin(q1 + q2) + my2 * std::cos(q1 + q2);
        return -(gx * mx + gy * my);
    };
    const auto& q1 = s.table.column("q1");
    const auto& q2 = s.table.column("q2");
    const double h = 1e-5;
    expect_everywhere(s, [&](std::size_t k) {
        return robot::Planar2R::Joints((potential(q1[k] + h, q2[k]) - potential(q1[k] - h, q2[k])) / (2 * h),
                                       (potential(q1[k], q2[k] + h) - potential(q1[k], q2[k] - h)) / (2 * h));
    }, 1e-7);
    EXPECT_NEAR(s.truth["effects"][0]["value"].get<double>(), gp * 1.5, 1e-12);
}

TEST(EffectInjection, TorqueDelayShiftsTheLoggedTorqueOnly) {
    const std::string plain = scratch("nodelay.csv"), delayed = scratch("delay.csv");
    ASSERT_EQ(simulate_log(plain, 2, 8, "--encoder-counts 0", "0").exit_code, 0);
    ASSERT_EQ(simulate_log(delayed, 2, 8, "--encoder-counts 0 --effect torque_delay:value=0.003", "0").exit_code, 0);
    const io::CsvTable a = io::read_csv(plain), b = io::read_csv(delayed);
    for (std::size_t k = 3; k < a.column("t").size(); ++k) {
        ASSERT_EQ(a.column("q1")[k], b.column("q1")[k]);
        ASSERT_NEAR(b.column("tau1")[k], a.column("tau1")[k - 3], 1e-8 * (1.0 + std::abs(a.column("tau1")[k - 3]))) << k;
        ASSERT_NEAR(b.column("tau2")[k], a.column("tau2")[k - 3], 1e-8 * (1.0 + std::abs(a.column("tau2")[k - 3]))) << k;
    }
}

TEST(EffectInjection, PreslidingIsTheDahlStateAlongTheTruePositions) {
    // Dahl's law ds/dx = (1 - s sgn(dx)) / x_p solved exactly between samples of the true position (s moves
    // towards the motion's sign by 1 - exp(-|dx| / x_p)), written out here. The simulator integrates it at its
    // substeps and holds it over each step, so the two agree to what one output sample of motion moves it.
    const States s = simulate_states("presliding", "--effect presliding:joint=2,value=0.25,displacement=8e-4");
    ASSERT_EQ(s.truth["effects"].size(), 1u);
    EXPECT_EQ(s.truth["effects"][0]["displacement"], 8e-4);
    const auto& q2 = s.table.column("q2");
    double state = 0.0, squared = 0.0, reference = 0.0;
    std::size_t saturated = 0;
    for (std::size_t k = 1; k < q2.size(); ++k) {
        const double dx = q2[k] - q2[k - 1];
        const double sign = dx > 0.0 ? 1.0 : dx < 0.0 ? -1.0 : 0.0;
        if (sign != 0.0) state = sign + (state - sign) * std::exp(-std::abs(dx) / 8e-4);
        const auto got = unexplained(s, k);
        ASSERT_NEAR(got[0], 0.0, 1e-9) << "joint 1 has no effect, sample " << k;
        const double want = 0.25 * state;
        squared += (got[1] - want) * (got[1] - want);
        reference += want * want;
        if (std::abs(state) > 0.999) {
            ++saturated;
            ASSERT_NEAR(got[1], want, 0.01 * 0.25) << "sliding, sample " << k;  // sliding: FD sgn(qd)
        }
    }
    EXPECT_GT(saturated, q2.size() / 2);
    EXPECT_LT(std::sqrt(squared / reference), 0.05);
}

TEST(EffectInjection, BadEffectsNameTheToken) {
    const std::string out = " --out " + scratch("bad.csv") + " --duration 1";
    const std::string sim = std::string(JACOBID_EXECUTABLE) + " simulate --robot " + diagnose_robot_yaml() + out;
    auto r = run_command(sim + " --effect cogging:joint=3,amplitude=0.1");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("cogging:joint=3,amplitude=0.1"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("joint 3 out of range"), std::string::npos) << r.err;
    r = run_command(sim + " --effect friction:value=1");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("unknown effect 'friction'"), std::string::npos) << r.err;
    const std::string yaml = scratch("effects.yaml");
    std::ofstream(yaml) << "effects:\n  - {name: coulomb_offset, joint: 1, value: 0.2}\n  - {name: stribeck, joint: 1, valeu: 0.3}\n";
    r = run_command(sim + " --effects " + yaml);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(yaml + ":3:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("unknown key 'valeu'"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace jacobid::test
