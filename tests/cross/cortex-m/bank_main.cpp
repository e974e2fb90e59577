// SPDX-License-Identifier: MIT
// What a Cortex-M firmware holds of jacobid: one 6-joint streaming bank (float, positions + torques in,
// aligned q^, qd^, qdd^ and delayed torque out), its kernels designed at start-up by configure(), then
// one step() per control cycle. Statically allocated; no heap, no OS, no exceptions.
// Inputs come from, and outputs go to, volatile "peripheral" buffers so that nothing is optimised away.
#include <jacobid/jacobid.hpp>

#include <array>
#include <cstdint>
#include <new>

namespace {

constexpr int kJoints = 6;
constexpr std::size_t kCapacity = JACOBID_BANK_CAPACITY;
using Bank = jacobid::DifferentiatorBank<float, kJoints, kCapacity>;

// The whole state of the estimator. A plain global `Bank bank;` works too, but its default member
// values are not all zero, so the linker would put it in .data and keep a ~47 KB copy of its initial
// image in flash. Constructed at start-up in zeroed .bss storage instead (placement new: no heap).
alignas(Bank) unsigned char bank_storage[sizeof(Bank)];

}  // namespace

// Stand-ins for an encoder/ADC interface and the telemetry buffer a DMA would send.
volatile float g_encoder[kJoints];
volatile float g_torque_sensor[kJoints];
volatile float g_estimates[4][kJoints];
volatile std::uint32_t g_status;
volatile std::uint32_t g_cycles;

int main() {
    Bank& bank = *new (bank_storage) Bank();
    std::array<jacobid::JointFilterConfig, kJoints> config{};
    for (auto& joint : config) {
        for (int c = 0; c < jacobid::kChannelCount; ++c) {
            jacobid::KernelParams& p = joint.params[static_cast<std::size_t>(c)];
            p.order = c;
            p.kappa = 6.0;
            p.mu = 6.0;
            p.q = 2;
            p.window = 0.21;  // 211 taps at 1 kHz
            p.sample_period = 1e-3;
            p.xi = 0.0;
        }
    }
    const jacobid::BankConfigResult r = bank.configure(config);
    g_status = static_cast<std::uint32_t>(r.status);
    if (r.status != jacobid::BankStatus::Ok) {
        for (;;) {}
    }

    Bank::Vector q, tau;
    Bank::Output out;
    for (;;) {  // the control loop: one sample per timer tick
        for (int j = 0; j < kJoints; ++j) {
            q[j] = g_encoder[j];
            tau[j] = g_torque_sensor[j];
        }
        if (bank.step(q, tau, out) == jacobid::BankStatus::Ok && out.valid) {
            for (int j = 0; j < kJoints; ++j) {
                g_estimates[0][j] = out.position[j];
                g_estimates[1][j] = out.velocity[j];
                g_estimates[2][j] = out.acceleration[j];
                g_estimates[3][j] = out.torque[j];
            }
        }
        g_cycles = g_cycles + 1;
    }
}
