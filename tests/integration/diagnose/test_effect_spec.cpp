// SPDX-License-Identifier: MIT
// Effect syntax (--effect tokens, effects YAML) and the effect columns' value conventions.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/errors.hpp"
#include "diagnose/blocked_grams.hpp"
#include "sim/effect_spec.hpp"

namespace jacobid::sim {
namespace {

std::string error_of(const std::string& token) {
    try {
        parse_effect(token, 2);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(EffectSpec, ParsesEveryEffect) {
    EffectSpec s = parse_effect("cogging:joint=2,amplitude=0.2,order=6,phase=30", 2);
    EXPECT_EQ(s.kind, EffectKind::Cogging);
    EXPECT_EQ(s.joint, 1);
    EXPECT_EQ(s.value, 0.2);
    EXPECT_EQ(s.order, 6);
    s = parse_effect("stribeck:joint=1,value=0.3,velocity=0.05", 2);
    EXPECT_EQ(s.velocity, 0.05);
    s = parse_effect("torque_delay:value=0.004", 2);
    EXPECT_EQ(s.joint, -1);
    EXPECT_EQ(s.value, 0.004);
    s = parse_effect("gravity:tilt=30,mx1=2", 2);
    EXPECT_NEAR(s.value, 9.80665 * 0.5 * 2.0, 1e-12);  // g sin(30 deg) mx1
    s = parse_effect("presliding:joint=2,value=0.4", 2);
    EXPECT_EQ(s.kind, EffectKind::Presliding);
    EXPECT_EQ(s.displacement, 5e-4);  // the default x_p
    EXPECT_EQ(parse_effect("presliding:joint=1,value=0.4,displacement=1e-3", 2).displacement, 1e-3);
    EXPECT_EQ(to_json(s)["displacement"], 5e-4);
    EXPECT_EQ(term_of(s).displacement, 5e-4);
    s = parse_effect("coulomb_smoothing:joint=1,value=0.2,alpha=30", 2);
    EXPECT_EQ(s.kind, EffectKind::CoulombSmoothing);
    EXPECT_EQ(term_of(s).alpha, 30.0);
    EXPECT_EQ(to_json(s)["alpha"], 30.0);
    EXPECT_NE(error_of("coulomb_smoothing:joint=1,value=0.2,alpha=0").find("alpha must be > 0"), std::string::npos);
    for (EffectKind k : kAllEffects) EXPECT_EQ(effect_kind(effect_name(k)), k);
}

TEST(EffectSpec, APreslidingDisplacementMustBePositive) {
    EXPECT_NE(error_of("presliding:joint=1,value=0.3,displacement=0").find("displacement must be within (0, 1] rad"), std::string::npos);
    EXPECT_NE(error_of("presliding:joint=1,value=0.3,displacement=-1e-4").find("key 'displacement'"), std::string::npos);
}

TEST(EffectSpec, ErrorsNameTheToken) {
    EXPECT_NE(error_of("coulomb_offset:joint=1").find("coulomb_offset needs 'value'"), std::string::npos);
    EXPECT_NE(error_of("coulomb_offset:joint=1,value=abc").find("'abc' is not a finite number"), std::string::npos);
    EXPECT_NE(error_of("coulomb_offset:joint=1,value=0.1,value=0.2").find("given twice"), std::string::npos);
    EXPECT_NE(error_of("cogging:joint=2,amplitude=0.1,order=2.5").find("order must be an integer"), std::string::npos);
    EXPECT_NE(error_of("rotor_inertia:joint=0,value=0.1").find("--effect 'rotor_inertia:joint=0,value=0.1'"), std::string::npos);
    EXPECT_NE(error_of("gravity:joint=1,tilt=3").find("unknown key 'joint' for gravity"), std::string::npos);
    EXPECT_NE(error_of("viscous_nonlinear:joint=1,0.2").find("'0.2' is not key=value"), std::string::npos);
}

TEST(EffectSpec, YamlErrorsNameFileLineAndColumn) {
    const auto specs = parse_effects_yaml("effects:\n  - {name: rotor_inertia, joint: 2, value: 0.1}\n  - {name: torque_delay, value: 0.002}\n", "e.yaml", 2);
    ASSERT_EQ(specs.size(), 2u);
    EXPECT_EQ(specs[1].kind, EffectKind::TorqueDelay);
    try {
        parse_effects_yaml("effects:\n  - {name: cogging, joint: 2, amplitude: 0.1, order: x}\n", "e.yaml", 2);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("e.yaml:2:"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("'order'"), std::string::npos) << e.what();
    }
}

TEST(EffectSpec, CoggingCoefficientsReproduceThePhase) {
    const EffectSpec s = parse_effect("cogging:joint=1,amplitude=0.2,order=7,phase=40", 2);
    const EffectTerm term = term_of(s);
    const EffectContext ctx{"planar2r", 2, {}, {}};
    // Dummy nominal model is not needed for cogging: coefficients depend on the spec only.
    struct NoModel : robot::RobotModel {
        std::vector<std::string> names;
        std::string model_name() const override { return "none"; }
        int joint_count() const override { return 2; }
        int parameter_count() const override { return 0; }
        const std::vector<std::string>& parameter_names() const override { return names; }
        void regressor(const double*, const double*, const double*, Eigen::Ref<Eigen::MatrixXd>) const override {}
    } none;
    const Eigen::VectorXd c = injected_coefficients(s, none, Eigen::VectorXd());
    Eigen::MatrixXd cols(2, 2);
    for (double q : {-2.0, 0.3, 1.7}) {
        const double qv[2] = {q, 0.0}, zero[2] = {0.0, 0.0};
        term_columns(term, ctx, qv, zero, zero, cols);
        EXPECT_NEAR(cols.row(0).dot(c), 0.2 * std::sin(7.0 * q + 40.0 * M_PI / 180.0), 1e-12);
        EXPECT_EQ(cols(1, 0), 0.0);
    }
    EXPECT_NEAR(term_value(term, c), 0.2, 1e-12);
}

TEST(BlockedGrams, MatchesADirectLeastSquaresSolve) {
    diagnose::DecimatedRows rows;
    std::mt19937_64 rng(3);
    std::normal_distribution<double> normal;
    const int m = 300, c = 4;
    for (int j = 0; j < 2; ++j) {
        Eigen::MatrixXd w(m, c);
        Eigen::VectorXd y(m);
        for (int i = 0; i < m; ++i) {
            for (int k = 0; k < c; ++k) w(i, k) = normal(rng);
            y[i] = normal(rng);
        }
        rows.w.push_back(w);
        rows.y.push_back(y);
    }
    rows.t.assign(m, 0.0);
    const diagnose::BlockedGrams grams(rows, 3);
    const std::vector<int> cols{0, 2, 3};
    const std::vector<double> weight2{1.0, 4.0};
    // Held-out block 1 excluded: rows [100, 200) of both joints, joint 2 weighted by 2.
    Eigen::MatrixXd A(2 * 200, 3);
    Eigen::VectorXd b(2 * 200);
    int r = 0;
    for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < m; ++i) {
            if (i >= 100 && i < 200) continue;
            A.row(r) = std::sqrt(weight2[j]) * rows.w[j](i, cols);
            b[r++] = std::sqrt(weight2[j]) * rows.y[j][i];
        }
    }
    const Eigen::VectorXd x = A.colPivHouseholderQr().solve(b);
    const auto fit = diagnose::solve_subset(grams.sum(cols, weight2, 1, true));
    ASSERT_TRUE(fit.ok);
    EXPECT_LT((fit.x - x).norm(), 1e-12 * x.norm());
    EXPECT_NEAR(fit.rss, (A * x - b).squaredNorm(), 1e-9 * fit.rss);
}

}  // namespace
}  // namespace jacobid::sim
