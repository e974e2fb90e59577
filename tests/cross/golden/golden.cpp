// SPDX-License-Identifier: MIT
// Prints the streaming bank's estimates (double and float) for a fixed input, one "name value" per line.
#include <jacobid/jacobid.hpp>

#include <array>
#include <cmath>
#include <cstdio>

namespace {

template <typename Scalar>
void run(const char* tag) {
    constexpr int J = 3;
    jacobid::DifferentiatorBank<Scalar, J, 256> bank;
    std::array<jacobid::JointFilterConfig, J> config{};
    const double windows[J] = {0.05, 0.1, 0.2};  // odd tap counts: whole-sample delays
    for (int j = 0; j < J; ++j) {
        for (int c = 0; c < jacobid::kChannelCount; ++c) {
            jacobid::KernelParams& p = config[j].params[c];
            p.order = c;
            p.kappa = 4.0 + j;
            p.mu = 6.0;
            p.q = 2;
            p.window = windows[j];
            p.sample_period = 1e-3;
            p.xi = 0.0;
        }
    }
    if (bank.configure(config).status != jacobid::BankStatus::Ok) {
        std::printf("configure failed\n");
        return;
    }
    using V = typename decltype(bank)::Vector;
    typename decltype(bank)::Output out;
    for (int k = 0; k < 600; ++k) {
        const double t = 1e-3 * k;
        V q, tau;
        for (int j = 0; j < J; ++j) {
            q[j] = static_cast<Scalar>(std::sin(2.0 * (j + 1) * t) + 0.3 * std::cos(7.0 * t) + 1e-3 * ((k * 7919 + j * 104729) % 17 - 8));
            tau[j] = static_cast<Scalar>(std::cos(3.0 * t + j));
        }
        bank.step(q, tau, out);
        if (out.valid && k % 37 == 0) {
            for (int j = 0; j < J; ++j) {
                std::printf("%s.q.%d.%d %.17g\n", tag, k, j, static_cast<double>(out.position[j]));
                std::printf("%s.qd.%d.%d %.17g\n", tag, k, j, static_cast<double>(out.velocity[j]));
                std::printf("%s.qdd.%d.%d %.17g\n", tag, k, j, static_cast<double>(out.acceleration[j]));
                std::printf("%s.tau.%d.%d %.17g\n", tag, k, j, static_cast<double>(out.torque[j]));
            }
        }
    }
    for (int j = 0; j < J; ++j) {
        const auto& kernel = bank.kernel(j, jacobid::kAcceleration);
        for (std::size_t i = 0; i < kernel.taps(); i += 7) std::printf("%s.w2.%d.%zu %.17g\n", tag, j, i, static_cast<double>(kernel.weights()[i]));
    }
}

}  // namespace

int main() {
    run<double>("d");
    run<float>("f");
    return 0;
}
