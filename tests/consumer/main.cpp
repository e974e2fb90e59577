// SPDX-License-Identifier: MIT
// Uses the installed core: a 2-joint streaming bank differentiating a ramp must report its slope.
#include <jacobid/jacobid.hpp>

#include <cmath>
#include <cstdio>

int main() {
    jacobid::DifferentiatorBank<double, 2, 128> bank;
    std::array<jacobid::JointFilterConfig, 2> config{};
    for (auto& joint : config) {
        for (int c = 0; c < 3; ++c) {
            joint.params[c].order = c;
            joint.params[c].window = 0.05;
            joint.params[c].sample_period = 1e-3;
        }
    }
    if (bank.configure(config).status != jacobid::BankStatus::Ok) return 1;
    jacobid::BankOutput<double, 2> out;
    for (int i = 0; i < 200; ++i) bank.step(Eigen::Vector2d(2.0 * i * 1e-3, -1.0), Eigen::Vector2d::Zero(), out);
    std::printf("velocity %.12f %.12f delay %zu samples\n", out.velocity[0], out.velocity[1], bank.delay_samples());
    return (out.valid && std::abs(out.velocity[0] - 2.0) < 1e-6 && std::abs(out.velocity[1]) < 1e-9) ? 0 : 1;
}
