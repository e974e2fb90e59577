// SPDX-License-Identifier: MIT
#pragma once
// A designed Jacobi differentiator: its parameters and FIR weights (oldest sample first) in fixed-size
// storage. Capacity is the largest number of taps it can hold.
#include <array>
#include <cstddef>
#include <type_traits>

#include "jacobid/kernel_design.hpp"
#include "jacobid/kernel_params.hpp"
#include "jacobid/span.hpp"

namespace jacobid {

template <typename Scalar, std::size_t Capacity>
class Kernel {
public:
    static constexpr std::size_t capacity = Capacity;

    // Designs in double (the weights of long windows span many orders of magnitude), stores as Scalar.
    // Any failure leaves the kernel not designed (taps() == 0), never the previous design: a caller that
    // misses the error must not go on filtering with weights for other parameters.
    KernelStatus design(const KernelParams& params) noexcept {
        if (const KernelStatus s = validate(params, Capacity); s != KernelStatus::Ok) {
            taps_ = 0;
            return s;
        }
        KernelStatus status;
        if constexpr (std::is_same_v<Scalar, double>) {
            weights_.fill(0.0);
            status = design_kernel(params, Span<double>(weights_));
        } else {
            std::array<double, Capacity> weights{};
            status = design_kernel(params, Span<double>(weights));
            for (std::size_t k = 0; k < Capacity; ++k) weights_[k] = static_cast<Scalar>(weights[k]);
        }
        if (status != KernelStatus::Ok) {
            taps_ = 0;
            return status;
        }
        params_ = params;
        taps_ = tap_count(params);
        return KernelStatus::Ok;
    }

    bool designed() const noexcept { return taps_ > 0; }
    std::size_t taps() const noexcept { return taps_; }
    const KernelParams& params() const noexcept { return params_; }
    Span<const Scalar> weights() const noexcept { return {weights_.data(), taps_}; }
    // Delay of the estimate behind the newest sample (fractional for most xi != 0).
    double delay_samples() const noexcept { return jacobid::delay_samples(params_); }
    double delay_seconds() const noexcept { return delay_samples() * params_.sample_period; }
    // Window actually used: (L - 1) Ts, which may differ from the requested T by up to Ts / 2.
    double effective_window() const noexcept { return static_cast<double>(taps_ - 1) * params_.sample_period; }

private:
    alignas(64) std::array<Scalar, Capacity> weights_{};
    std::size_t taps_ = 0;
    KernelParams params_{};
};

}  // namespace jacobid
