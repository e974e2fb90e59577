// SPDX-License-Identifier: MIT
// 01: the real-time core. A bank of Jacobi differentiators estimates velocity and acceleration of two joints
// from quantized encoder positions, one sample at a time, without heap (what jacobid-fw runs each cycle).
#include <jacobid/jacobid.hpp>

#include <cmath>
#include <cstdio>

int main() {
    constexpr double ts = 1e-3, pi = 3.14159265358979323846;
    // Per joint and channel (0: position, 1: velocity, 2: acceleration): a central Jacobi kernel over 0.1 s.
    std::array<jacobid::JointFilterConfig, 2> config{};
    for (auto& joint : config) {
        for (int c = 0; c < 3; ++c) {
            joint.params[c].order = c;
            joint.params[c].window = 0.1;
            joint.params[c].sample_period = ts;
        }
    }
    jacobid::DifferentiatorBank<double, 2, 256> bank;  // 2 joints, up to 256 taps per kernel
    const jacobid::BankConfigResult result = bank.configure(config);
    if (result.status != jacobid::BankStatus::Ok) {
        std::printf("configure: %s\n", jacobid::describe(result.status));
        return 1;
    }
    // The estimates describe the motion delay_samples() ago (half the window for central kernels).
    const double delay = static_cast<double>(bank.delay_samples()) * ts;
    std::printf("delay %zu samples (%.3f s)\n", bank.delay_samples(), delay);

    // Joint 1 follows 0.5 sin(2 pi t), joint 2 0.2 sin(2 pi 0.5 t), read by 2^16-count encoders.
    const double amplitude[2] = {0.5, 0.2}, frequency[2] = {1.0, 0.5}, count = 2.0 * pi / 65536.0;
    jacobid::BankOutput<double, 2> out;
    double worst_velocity = 0.0, worst_acceleration = 0.0;
    for (int k = 0; k < 3000; ++k) {
        const double t = k * ts;
        Eigen::Vector2d q, tau = Eigen::Vector2d::Zero();
        for (int j = 0; j < 2; ++j) q[j] = count * std::round(amplitude[j] * std::sin(2 * pi * frequency[j] * t) / count);
        bank.step(q, tau, out);
        if (!out.valid) continue;  // until every window is full
        for (int j = 0; j < 2; ++j) {
            const double w = 2 * pi * frequency[j], td = t - delay;
            worst_velocity = std::max(worst_velocity, std::abs(out.velocity[j] - amplitude[j] * w * std::cos(w * td)));
            worst_acceleration = std::max(worst_acceleration, std::abs(out.acceleration[j] + amplitude[j] * w * w * std::sin(w * td)));
        }
        if (k % 500 == 0) std::printf("t %.1f s  qd^ %+.4f %+.4f rad/s  qdd^ %+.3f %+.3f rad/s^2\n", t, out.velocity[0], out.velocity[1], out.acceleration[0], out.acceleration[1]);
    }
    // Peaks are 3.14 rad/s and 19.7 rad/s^2 on joint 1: a missed delay or a wrong gain is far above this.
    std::printf("largest error: velocity %.2g rad/s, acceleration %.2g rad/s^2\n", worst_velocity, worst_acceleration);
    return worst_velocity < 0.02 && worst_acceleration < 0.5 ? 0 : 1;
}
