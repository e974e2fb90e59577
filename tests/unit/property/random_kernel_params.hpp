// SPDX-License-Identifier: MIT
#pragma once
// Random Jacobi differentiator parameters for the property tests: inside the ranges validate() accepts
// (kernel_params.hpp), or with exactly one parameter pushed outside them. Fixed seeds: a failure names the
// case index, and the same case comes back on every run.
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>

#include "jacobid/kernel_params.hpp"

namespace jacobid::test {

class RandomParams {
public:
    explicit RandomParams(std::uint64_t seed) : rng_(seed) {}

    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
    int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
    bool coin() { return integer(0, 1) == 1; }
    // Log-uniform: sample periods and amplitudes span decades.
    double decades(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }

    // kappa, mu > -1: mostly the useful 0..10, sometimes close to the bound (singular weight ends) or large.
    double exponent() {
        switch (integer(0, 3)) {
            case 0: return -1.0 + decades(1e-6, 0.999);
            case 1: return uniform(10.0, 40.0);
            default: return uniform(0.0, 10.0);
        }
    }

    // Valid parameters of order n with `taps` taps (>= 3) at a random sample period.
    KernelParams valid(int order, std::size_t taps) {
        KernelParams p;
        p.order = order;
        p.kappa = exponent();
        p.mu = exponent();
        p.q = integer(0, 6);
        p.sample_period = decades(1e-5, 1e-1);
        p.window = static_cast<double>(taps - 1) * p.sample_period;
        p.xi = coin() ? uniform(-1.0, 1.0) : (coin() ? 0.0 : 1.0);
        p.discretization = coin() ? Discretization::Exact : Discretization::Trapezoidal;
        return p;
    }

private:
    std::mt19937_64 rng_;
};

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace jacobid::test
