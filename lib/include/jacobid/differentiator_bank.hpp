// SPDX-License-Identifier: MIT
#pragma once
// Streaming differentiator bank: per joint, position q^ (n = 0), velocity qd^ (n = 1) and acceleration
// qdd^ (n = 2) estimates, each from its own Jacobi kernel, plus the raw torque, all delayed to one common
// delay so that a row of outputs describes one instant (docs/method.md, "Streaming alignment").
//
// Model/Data split (Pinocchio style): configure() designs the kernels once; step() only reads them and
// the ring buffers. Nothing allocates; step() costs 3 dot products per joint.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <Eigen/Core>

#include "jacobid/dot_product.hpp"
#include "jacobid/kernel.hpp"
#include "jacobid/kernel_params.hpp"
#include "jacobid/ring_window.hpp"

namespace jacobid {

// Index of the three estimates of a joint.
enum Channel : int { kPosition = 0, kVelocity = 1, kAcceleration = 2, kChannelCount = 3 };

struct JointFilterConfig {
    // params[c].order must equal c (0 position, 1 velocity, 2 acceleration).
    std::array<KernelParams, kChannelCount> params{};
};

enum class BankStatus {
    Ok,
    NotConfigured,          // step() before a successful configure()
    InvalidKernel,          // a kernel's parameters were rejected: see BankConfigResult::kernel_status
    OrderMismatch,          // params[c].order != c
    SamplePeriodMismatch,   // all kernels must share the sample period
    DelayNotAlignable,      // the delays do not differ by whole samples, or the common delay is fractional
    AlignmentExceedsCapacity,  // a kernel plus its alignment lag does not fit in the ring capacity
};

inline const char* describe(BankStatus s) noexcept {
    switch (s) {
        case BankStatus::Ok: return "ok";
        case BankStatus::NotConfigured: return "bank used before a successful configure()";
        case BankStatus::InvalidKernel: return "a kernel's parameters are invalid";
        case BankStatus::OrderMismatch: return "channel order mismatch: position needs order 0, velocity 1, acceleration 2";
        case BankStatus::SamplePeriodMismatch: return "all kernels of a bank must use the same sample period";
        case BankStatus::DelayNotAlignable:
            return "kernel delays h(1-xi) must be whole numbers of samples to be aligned (use an odd tap count for central kernels)";
        case BankStatus::AlignmentExceedsCapacity: return "a kernel plus its alignment delay exceeds the ring capacity";
    }
    return "unknown bank status";
}

struct BankConfigResult {
    BankStatus status = BankStatus::Ok;
    KernelStatus kernel_status = KernelStatus::Ok;  // when status == InvalidKernel
    std::size_t joint = 0;                          // first offending joint and channel
    int channel = 0;
};

template <typename Scalar, int Joints>
struct BankOutput {
    using Vector = Eigen::Matrix<Scalar, Joints, 1>;
    Vector position = Vector::Zero();
    Vector velocity = Vector::Zero();
    Vector acceleration = Vector::Zero();
    Vector torque = Vector::Zero();        // raw torque delayed by the common delay
    Vector raw_position = Vector::Zero();  // raw measured position delayed by the common delay
    std::uint64_t sample_index = 0;  // index of the input sample these estimates refer to
    bool valid = false;              // false during warm-up, until every window is full
};

template <typename Scalar, int Joints, std::size_t Capacity>
class DifferentiatorBank {
    static_assert(Joints > 0, "a bank needs at least one joint");

public:
    using Vector = Eigen::Matrix<Scalar, Joints, 1>;
    using Output = BankOutput<Scalar, Joints>;

    BankConfigResult configure(const std::array<JointFilterConfig, Joints>& config) noexcept {
        configured_ = false;
        BankConfigResult result;
        double max_delay = 0.0;
        const double ts = config[0].params[0].sample_period;
        for (std::size_t j = 0; j < Joints; ++j) {
            for (int c = 0; c < kChannelCount; ++c) {
                const KernelParams& p = config[j].params[c];
                result.joint = j;
                result.channel = c;
                if (p.order != c) return fail(result, BankStatus::OrderMismatch);
                if (p.sample_period != ts) return fail(result, BankStatus::SamplePeriodMismatch);
                result.kernel_status = kernels_[j][c].design(p);
                if (result.kernel_status != KernelStatus::Ok) return fail(result, BankStatus::InvalidKernel);
                max_delay = std::max(max_delay, kernels_[j][c].delay_samples());
            }
        }
        const double rounded = std::round(max_delay);
        if (std::abs(max_delay - rounded) > 1e-9) return fail(result, BankStatus::DelayNotAlignable);
        common_delay_ = static_cast<std::size_t>(rounded);
        warmup_ = common_delay_ + 1;
        for (std::size_t j = 0; j < Joints; ++j) {
            for (int c = 0; c < kChannelCount; ++c) {
                result.joint = j;
                result.channel = c;
                const double lag = rounded - kernels_[j][c].delay_samples();
                if (std::abs(lag - std::round(lag)) > 1e-9) return fail(result, BankStatus::DelayNotAlignable);
                lag_[j][c] = static_cast<std::size_t>(std::round(lag));
                if (kernels_[j][c].taps() + lag_[j][c] > Capacity) return fail(result, BankStatus::AlignmentExceedsCapacity);
                warmup_ = std::max(warmup_, kernels_[j][c].taps() + lag_[j][c]);
            }
        }
        if (common_delay_ + 1 > Capacity) return fail(result, BankStatus::AlignmentExceedsCapacity);
        sample_period_ = ts;
        reset();
        configured_ = true;
        return BankConfigResult{};
    }

    // Clears the history (e.g. after a gap in the data); the kernels stay.
    void reset() noexcept {
        for (auto& r : positions_) r.reset();
        for (auto& r : torques_) r.reset();
        ticks_ = 0;
    }

    // One sample of every joint in, one aligned row of estimates out.
    BankStatus step(const Vector& position, const Vector& torque, Output& out) noexcept {
        if (!configured_) return BankStatus::NotConfigured;
        for (int j = 0; j < Joints; ++j) {
            positions_[j].push(position[j]);
            torques_[j].push(torque[j]);
        }
        ++ticks_;
        for (int j = 0; j < Joints; ++j) {
            const auto& ring = positions_[j];
            out.position[j] = apply(ring, j, kPosition);
            out.velocity[j] = apply(ring, j, kVelocity);
            out.acceleration[j] = apply(ring, j, kAcceleration);
            out.torque[j] = torques_[j].at_lag(common_delay_);
            out.raw_position[j] = ring.at_lag(common_delay_);
        }
        out.valid = ticks_ >= warmup_;
        out.sample_index = ticks_ > common_delay_ ? ticks_ - 1 - common_delay_ : 0;
        return BankStatus::Ok;
    }

    bool configured() const noexcept { return configured_; }
    std::size_t delay_samples() const noexcept { return common_delay_; }
    double delay_seconds() const noexcept { return static_cast<double>(common_delay_) * sample_period_; }
    // Ticks until the first valid output.
    std::size_t warmup_samples() const noexcept { return warmup_; }
    const Kernel<Scalar, Capacity>& kernel(std::size_t joint, int channel) const noexcept { return kernels_[joint][channel]; }

private:
    Scalar apply(const RingWindow<Scalar, Capacity>& ring, int joint, int channel) const noexcept {
        const auto& k = kernels_[joint][channel];
        return dot_product(ring.window(k.taps(), lag_[joint][channel]), k.weights().data(), k.taps());
    }

    static BankConfigResult fail(BankConfigResult r, BankStatus s) noexcept {
        r.status = s;
        return r;
    }

    std::array<std::array<Kernel<Scalar, Capacity>, kChannelCount>, Joints> kernels_{};
    std::array<std::array<std::size_t, kChannelCount>, Joints> lag_{};
    std::array<RingWindow<Scalar, Capacity>, Joints> positions_{};
    std::array<RingWindow<Scalar, Capacity>, Joints> torques_{};
    std::size_t common_delay_ = 0;
    std::size_t warmup_ = 0;
    std::uint64_t ticks_ = 0;
    double sample_period_ = 0.0;
    bool configured_ = false;
};

}  // namespace jacobid
