// SPDX-License-Identifier: MIT
// Jacobi polynomials against closed forms and direct numerical integration (independent references).
#include <gtest/gtest.h>

#include <cmath>

#include "jacobid/jacobi_polynomial.hpp"

namespace {

using jacobid::jacobi_p;

TEST(JacobiPolynomial, MatchesClosedForms) {
    for (double x : {-1.0, -0.7, 0.0, 0.3, 1.0}) {
        // Legendre (a = b = 0): P2 = (3x^2 - 1)/2, P3 = (5x^3 - 3x)/2.
        EXPECT_NEAR(jacobi_p(2, 0, 0, x), 0.5 * (3 * x * x - 1), 1e-14);
        EXPECT_NEAR(jacobi_p(3, 0, 0, x), 0.5 * (5 * x * x * x - 3 * x), 1e-14);
        // P1^{(a,b)} = (a + 1) + (a + b + 2)(x - 1)/2 (Abramowitz-Stegun 22.3.2 with n = 1).
        EXPECT_NEAR(jacobi_p(1, 2.5, -0.5, x), 3.5 + 4.0 * (x - 1) / 2, 1e-14);
    }
    // P_i(1) = C(i + a, i).
    EXPECT_NEAR(jacobi_p(4, 3.0, 7.0, 1.0), 35.0, 1e-11);  // C(7, 4)
    // Symmetry P_i^{(a,b)}(-x) = (-1)^i P_i^{(b,a)}(x).
    EXPECT_NEAR(jacobi_p(5, 1.5, 4.0, -0.37), -jacobi_p(5, 4.0, 1.5, 0.37), 1e-12);
}

TEST(JacobiPolynomial, NormAndOrthogonalityByQuadrature) {
    const double a = 2.0, b = 3.5;
    const int m = 200000;  // composite midpoint rule on a smooth integrand
    for (int i = 0; i <= 5; ++i) {
        for (int j = 0; j <= i; ++j) {
            double sum = 0;
            for (int k = 0; k < m; ++k) {
                const double x = -1.0 + (k + 0.5) * 2.0 / m;
                sum += std::pow(1 - x, a) * std::pow(1 + x, b) * jacobi_p(i, a, b, x) * jacobi_p(j, a, b, x);
            }
            sum *= 2.0 / m;
            const double expected = (i == j) ? jacobid::jacobi_norm_squared(i, a, b) : 0.0;
            EXPECT_NEAR(sum, expected, 1e-7 * jacobid::jacobi_norm_squared(i, a, b)) << i << "," << j;
        }
    }
}

TEST(JacobiPolynomial, DerivativeMatchesFiniteDifference) {
    const double a = 6.0, b = 4.0, x = 0.21, e = 1e-4;
    for (int i = 1; i <= 6; ++i) {
        const double fd = (jacobi_p(i, a, b, x + e) - jacobi_p(i, a, b, x - e)) / (2 * e);
        EXPECT_NEAR(jacobid::jacobi_p_derivative(i, a, b, 1, x), fd, 1e-5 * std::abs(fd) + 1e-8);
        const double fd2 = (jacobi_p(i, a, b, x + e) - 2 * jacobi_p(i, a, b, x) + jacobi_p(i, a, b, x - e)) / (e * e);
        EXPECT_NEAR(jacobid::jacobi_p_derivative(i, a, b, 2, x), fd2, 1e-4 * std::abs(fd2) + 1e-5);
    }
    EXPECT_EQ(jacobid::jacobi_p_derivative(2, a, b, 3, x), 0.0);
}

TEST(JacobiPolynomial, LargestRootOfGegenbauerCase) {
    // P_2^{(c,c)} is proportional to the Gegenbauer C_2^{c+1/2}: roots +-sqrt(1/(2c + 3)).
    for (double c : {0.0, 1.0, 6.5, 13.0}) {
        EXPECT_NEAR(jacobid::jacobi_largest_root(2, c, c), std::sqrt(1.0 / (2 * c + 3)), 1e-13);
    }
    // Legendre P3: largest root sqrt(3/5).
    EXPECT_NEAR(jacobid::jacobi_largest_root(3, 0, 0), std::sqrt(0.6), 1e-13);
    // An asymmetric case: the result is a root and nothing above it changes sign.
    const double r = jacobid::jacobi_largest_root(7, 8.0, 3.0);
    EXPECT_NEAR(jacobi_p(7, 8.0, 3.0, r), 0.0, 1e-10);
    for (double x = r + 1e-6; x <= 1.0; x += 1e-4) EXPECT_GT(jacobi_p(7, 8.0, 3.0, x), 0.0);
}

}  // namespace
