// SPDX-License-Identifier: MIT
// excite --criterion i-optimal (docs/excite.md, "Designing for the motion the model will serve"), against
// independent checks: its gradient against central differences of the criterion; the predicted rms torque error
// over the reference motion (Prediction::reference_rms) against the spread of the model's torque over that motion
// when the WLS estimate is solved again and again on simulated noise (linear algebra alone); the default
// reference's random moves within the limits (from finite differences of its positions, not its own columns);
// the command: the design predicts less error on its reference than a d-optimal design of the same duration,
// the reference's figure in the JSON, and the options it refuses.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "excite/information_criterion.hpp"
#include "excite/reference_motion.hpp"
#include "robot/robot_description.hpp"
#include "run_command.hpp"
#include "excite_test_support.hpp"

namespace {

using jacobid::test::run_command;
using namespace jacobid;
using test::kJacobid;
using test::kTwoLink;

std::string scratch(const std::string& name) { return test::excite_scratch("excite_reference", name); }

Eigen::MatrixXd random_rows(int rows, int columns, std::mt19937_64& rng) {
    std::normal_distribution<double> normal;
    Eigen::MatrixXd W(rows, columns);
    for (Eigen::Index i = 0; i < W.size(); ++i) W.data()[i] = normal(rng) * (1.0 + static_cast<double>(i % 4));
    return W;
}

// M of stacked rows R (sample-major, joint-minor) written out as its definition: the mean over samples of
// sum_j r_ij^T r_ij / sigma_j^2.
Eigen::MatrixXd mean_information(const Eigen::MatrixXd& R, const Eigen::VectorXd& sigma) {
    const auto joints = sigma.size();
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(R.cols(), R.cols());
    for (Eigen::Index r = 0; r < R.rows(); ++r) M += R.row(r).transpose() * R.row(r) / (sigma[r % joints] * sigma[r % joints]);
    return M / static_cast<double>(R.rows() / joints);
}

TEST(IOptimal, GradientInWMatchesCentralDifferences) {
    std::mt19937_64 rng(3);
    const int joints = 3, p = 7;
    const Eigen::MatrixXd W = random_rows(12 * joints, p, rng);
    const Eigen::Vector3d sigma(0.5, 0.2, 0.05);
    excite::InformationModel model{sigma, Eigen::VectorXd::LinSpaced(p, 0.1, 3.0), 7.0, {}, mean_information(random_rows(30 * joints, p, rng), sigma)};
    EXPECT_LT(test::criterion_gradient_error(excite::Criterion::IOptimal, W, joints, model, 5), 1e-5);
    // Without a reference of the parameters' size the criterion is refused, not evaluated against garbage.
    model.reference = Eigen::MatrixXd::Identity(p - 1, p - 1);
    EXPECT_THROW(excite::evaluate_criterion(excite::Criterion::IOptimal, W, joints, model, nullptr), std::invalid_argument);
}

TEST(IOptimal, ReferenceRmsIsTheSpreadOfTheModelsTorqueOverTheReferenceOnSimulatedNoise) {
    // y = W x + e, e_j ~ N(0, sigma_j^2): the WLS estimate solved 4000 times; the model's torque error R (x^ - x) on a
    // reference motion R, per joint over sigma_j, mean square over the reference's samples and summed over joints.
    std::mt19937_64 rng(5);
    std::normal_distribution<double> normal;
    const int joints = 2, p = 5;
    const Eigen::MatrixXd W = random_rows(60 * joints, p, rng), R = random_rows(25 * joints, p, rng);
    const Eigen::Vector2d sigma(0.3, 0.05);
    const Eigen::MatrixXd M = mean_information(R, sigma);
    const excite::Prediction predicted = excite::predict(excite::information_matrix(W, joints, sigma, 1.0), Eigen::VectorXd::Ones(p), &M);
    ASSERT_TRUE(predicted.identifiable);
    Eigen::MatrixXd weighted = W;
    for (Eigen::Index r = 0; r < W.rows(); ++r) weighted.row(r) /= sigma[r % joints];
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(weighted);
    const int runs = 4000;
    double sum = 0.0;
    for (int k = 0; k < runs; ++k) {
        Eigen::VectorXd y(W.rows());
        for (Eigen::Index r = 0; r < W.rows(); ++r) y[r] = normal(rng);  // the weighted noise, unit variance; x = 0
        const Eigen::VectorXd error = R * qr.solve(y);
        for (Eigen::Index r = 0; r < R.rows(); ++r) sum += (error[r] / sigma[r % joints]) * (error[r] / sigma[r % joints]);
    }
    const double measured = std::sqrt(sum / runs / static_cast<double>(R.rows() / joints));
    EXPECT_NEAR(measured / predicted.reference_rms, 1.0, 0.03);
    // No reference: no figure.
    EXPECT_TRUE(std::isnan(excite::predict(excite::information_matrix(W, joints, sigma, 1.0), Eigen::VectorXd::Ones(p)).reference_rms));
}

TEST(IOptimal, DefaultReferenceMovesStayWithinThePositionVelocityAndAccelerationLimits) {
    std::vector<excite::JointLimits> limits(2);
    limits[0].lower = -1.0, limits[0].upper = 2.0, limits[0].velocity = 1.5, limits[0].acceleration = 4.0;
    limits[1].lower = -0.5, limits[1].upper = 0.5, limits[1].velocity = 0.8, limits[1].acceleration = 2.0;
    const double rate = 1000.0;
    const excite::SampledMotion m = excite::random_moves(limits, Eigen::Vector2d(0.5, 0.0), 30.0, rate, 1);
    ASSERT_EQ(m.samples(), 30001u);
    for (std::size_t j = 0; j < 2; ++j) {
        double travelled = 0.0;
        for (std::size_t i = 1; i + 1 < m.samples(); ++i) {
            EXPECT_GE(m.q[j][i], limits[j].lower - 1e-12);
            EXPECT_LE(m.q[j][i], limits[j].upper + 1e-12);
            const double v = (m.q[j][i + 1] - m.q[j][i - 1]) * rate / 2.0, a = (m.q[j][i + 1] - 2.0 * m.q[j][i] + m.q[j][i - 1]) * rate * rate;
            EXPECT_LE(std::abs(v), limits[j].velocity * 1.001) << "joint " << j << " sample " << i;
            EXPECT_LE(std::abs(a), limits[j].acceleration * 1.01) << "joint " << j << " sample " << i;
            travelled += std::abs(m.q[j][i + 1] - m.q[j][i]);
        }
        EXPECT_GT(travelled, 5.0 * (limits[j].upper - limits[j].lower)) << "joint " << j << " hardly moves";
    }
    // Seeded: the same seed, the same motion; another seed, another.
    EXPECT_EQ(excite::random_moves(limits, Eigen::Vector2d(0.5, 0.0), 30.0, rate, 1).q, m.q);
    EXPECT_NE(excite::random_moves(limits, Eigen::Vector2d(0.5, 0.0), 30.0, rate, 2).q, m.q);
}

TEST(ExciteCli, IOptimalDesignPredictsLessErrorOnItsReferenceThanTheDOptimalDesign) {
    const std::string common = " --robot " + kTwoLink + " --duration 20 --velocity-limit 2 --acceleration-limit 8 --torque-noise 0.05,0.01 --time-limit 600 "
                               "--max-evaluations 300 --starts 2 --quiet";
    const std::string reference = scratch("reference.csv"), dopt = scratch("dopt.csv"), iopt = scratch("iopt.json");
    // The reference: 60 s of random moves within the same limits (what the model will serve), a log of the simulator.
    ASSERT_EQ(run_command(kJacobid + " simulate --quiet --robot " + kTwoLink + " --duration 60 --velocity-limit 2 --acceleration-limit 8 --seed 77 -o " +
                          reference).exit_code, 0);
    const auto d = run_command(kJacobid + " excite" + common + " -o " + dopt);
    ASSERT_EQ(d.exit_code, 0) << d.err;
    const auto i = run_command(kJacobid + " excite" + common + " --criterion i-optimal --reference " + reference + " --compare " + dopt + " -o " +
                               scratch("iopt.csv") + " --json " + iopt);
    ASSERT_EQ(i.exit_code, 0) << i.err;
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(iopt));
    EXPECT_EQ(j["criterion"], "i-optimal");
    const double mine = j["predicted"]["reference_rms"].get<double>(), theirs = j["compare"]["predicted"]["reference_rms"].get<double>();
    EXPECT_GT(mine, 0.0);
    EXPECT_LT(mine, theirs) << "the i-optimal design predicts more error on its own reference than the d-optimal design";
    EXPECT_FALSE(j["compare"]["design_worse"].get<bool>());
    EXPECT_NEAR(j["predicted"]["score"].get<double>(), 2.0 * std::log(mine), 1e-12);
    // Without --quiet, the text gives the figure too.
    const auto text = run_command(kJacobid + " excite" + common.substr(0, common.size() - 8) + " --criterion i-optimal --reference " + reference +
                                  " -o " + scratch("iopt_text.csv"));
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.err.find("excite: predicted rms error of the model's torque over the reference (" + reference + ")"), std::string::npos) << text.err;
    // The default reference (random moves within the design's limits) runs too; a payload design is refused in one line.
    const auto def = run_command(kJacobid + " excite" + common + " --criterion i-optimal -o " + scratch("default.csv") + " --json " + scratch("default.json"));
    ASSERT_EQ(def.exit_code, 0) << def.err;
    EXPECT_GT(nlohmann::json::parse(std::ifstream(scratch("default.json")))["predicted"]["reference_rms"].get<double>(), 0.0);
    const auto bad = run_command(kJacobid + " excite" + common + " --criterion i-optimal --payload --payload-mass 1 -o " + scratch("bad.csv"));
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_NE(bad.err.find("--criterion i-optimal: not with --payload"), std::string::npos) << bad.err;
    // A reference the criterion would not use is refused, not ignored.
    const auto unused = run_command(kJacobid + " excite" + common + " --reference " + reference + " -o " + scratch("unused.csv"));
    EXPECT_NE(unused.exit_code, 0);
    EXPECT_NE(unused.err.find("--reference " + reference + ": used by --criterion i-optimal only (the criterion is d-optimal)"), std::string::npos) << unused.err;
}

}  // namespace
