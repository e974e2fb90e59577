// SPDX-License-Identifier: MIT
#pragma once
// Fixed-capacity ring buffer whose latest Capacity samples are always contiguous in memory: every sample
// is written twice, at i and i + Capacity, so any window ending at the newest sample is one pointer and
// the FIR dot product needs no per-tap index arithmetic or wrap-around.
#include <array>
#include <cstddef>

namespace jacobid {

template <typename Scalar, std::size_t Capacity>
class RingWindow {
    static_assert(Capacity > 0, "RingWindow needs a capacity of at least one sample");

public:
    static constexpr std::size_t capacity = Capacity;

    void push(Scalar x) noexcept {
        buffer_[head_] = x;
        buffer_[head_ + Capacity] = x;
        head_ = (head_ + 1 == Capacity) ? 0 : head_ + 1;
        if (count_ < Capacity) ++count_;
    }

    // The `length` samples ending `lag` samples before the newest one, oldest first.
    // Requires length + lag <= Capacity; samples not yet pushed read as zero (see filled()).
    const Scalar* window(std::size_t length, std::size_t lag = 0) const noexcept {
        return buffer_.data() + head_ + Capacity - length - lag;
    }

    // Sample pushed `lag` pushes ago (0 = newest).
    Scalar at_lag(std::size_t lag) const noexcept { return *window(1, lag); }

    // Number of samples pushed so far, saturating at Capacity.
    std::size_t filled() const noexcept { return count_; }

    void reset() noexcept {
        buffer_.fill(Scalar(0));
        head_ = 0;
        count_ = 0;
    }

private:
    alignas(64) std::array<Scalar, 2 * Capacity> buffer_{};
    std::size_t head_ = 0;
    std::size_t count_ = 0;
};

}  // namespace jacobid
