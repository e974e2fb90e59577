// SPDX-License-Identifier: MIT
// Statistics of the selection against independent references: scipy.stats.chi2.sf values (computed with
// Debian's /usr/bin/python3: `from scipy.stats import chi2; chi2.sf(x, k)`), the AR(1) effective sample
// size n (1 - phi) / (1 + phi), and blocked normal equations against a direct QR least-squares solve.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "diagnose/statistics.hpp"

namespace jacobid::diagnose {
namespace {

TEST(DiagnoseStatistics, ChiSquareSurvivalMatchesScipy) {
    struct Ref {
        double x;
        int dof;
        double sf;
    };
    const Ref refs[] = {
        {0.5, 1, 0.47950012218695337},   {3.84, 1, 0.050043521248705189}, {10, 1, 0.001565402258002549},
        {30, 1, 4.3204630578274955e-08}, {5.99, 2, 0.050036627086586287}, {20, 2, 4.5399929762484861e-05},
        {9.49, 4, 0.049953131223294894}, {40, 4, 4.3284226071209661e-08}, {2.5, 3, 0.4752910833430205},
        {25, 5, 0.00013933379118562629}, {60, 2, 9.3576229688401635e-14}, {150, 1, 1.7336432457178413e-34},
    };
    for (const auto& r : refs) EXPECT_NEAR(chi_square_survival(r.x, r.dof), r.sf, 1e-12 * r.sf + 1e-300) << r.x << " " << r.dof;
    EXPECT_EQ(chi_square_survival(0.0, 3), 1.0);
}

TEST(DiagnoseStatistics, EffectiveSampleSizeOfAnAr1Series) {
    std::mt19937_64 rng(7);
    std::normal_distribution<double> normal;
    for (double phi : {0.0, 0.5, 0.8}) {
        const int n = 40000;
        Eigen::VectorXd x(n);
        double state = 0.0;
        for (int i = 0; i < n; ++i) x[i] = state = phi * state + normal(rng);
        const double expected = n * (1.0 - phi) / (1.0 + phi);
        EXPECT_NEAR(effective_sample_size(x), expected, 0.15 * expected) << "phi " << phi;
        const auto rho = autocorrelation(x, 3);
        EXPECT_NEAR(rho[0], phi, 0.02);
        EXPECT_NEAR(rho[1], phi * phi, 0.03);
    }
}

}  // namespace
}  // namespace jacobid::diagnose
