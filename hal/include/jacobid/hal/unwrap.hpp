// SPDX-License-Identifier: MIT
#pragma once
// Multi-turn unwrapping. Devices report a position that wraps: MIT-mode replies at the ends of their
// 16-bit range, CiA 402 at the INT32 limits (or every turn with a modulo position range), single-turn
// encoders every revolution. The unwrapper assumes consecutive samples move by less than half a period
// (at 1 kHz and a 16-bit MIT range of 25 rad that is 12.5 rad per ms: any real joint) and counts turns.
//
// CountUnwrapper works on integer counts so that the unwrapped count is exact however many turns go by;
// convert to radians only after unwrapping. PeriodUnwrapper does the same for a floating-point value.
#include <cstdint>

namespace jacobid::hal {

class CountUnwrapper {
public:
    // modulus: counts per period (2^16 for a 16-bit code, 2^32 for an INT32 position, the counts per
    // revolution of a single-turn encoder). 0 means "never wraps".
    explicit constexpr CountUnwrapper(std::uint64_t modulus = 0) noexcept : modulus_(modulus) {}

    void set_modulus(std::uint64_t modulus) noexcept {
        modulus_ = modulus;
        reset();
    }
    void reset() noexcept { initialized_ = false; }

    // `raw` is the reported count as the device means it (sign-extended when the field is signed, so
    // that the first sample lands on the right side of zero). Returns the unwrapped count.
    std::int64_t update(std::int64_t raw) noexcept {
        if (!initialized_) {
            initialized_ = true;
            last_raw_ = raw;
            unwrapped_ = raw;
            return unwrapped_;
        }
        // Difference modulo the period, brought into [-M/2, M/2). The true difference raw - last is
        // taken on unsigned 64-bit in the direction where it is non-negative, so neither INT32 inputs
        // nor a modulus that is not a power of two can overflow or bias it.
        std::int64_t delta;
        if (modulus_ == 0) {
            // Two's-complement difference: a 64-bit field that jumps by more than 2^63 (a corrupt frame, never
            // a joint) wraps instead of overflowing a signed subtraction (undefined behaviour).
            delta = static_cast<std::int64_t>(static_cast<std::uint64_t>(raw) - static_cast<std::uint64_t>(last_raw_));
        } else {
            const std::uint64_t m = modulus_;
            const auto ur = static_cast<std::uint64_t>(raw);
            const auto ul = static_cast<std::uint64_t>(last_raw_);
            std::uint64_t d;
            if (raw >= last_raw_) {
                d = (ur - ul) % m;
            } else {
                const std::uint64_t back = (ul - ur) % m;
                d = back == 0 ? 0 : m - back;
            }
            delta = d >= (m + 1) / 2 ? -static_cast<std::int64_t>(m - d) : static_cast<std::int64_t>(d);
        }
        last_raw_ = raw;
        // Modulo 2^64 like the difference above: turns counted past the int64 range wrap, never trap.
        unwrapped_ = static_cast<std::int64_t>(static_cast<std::uint64_t>(unwrapped_) + static_cast<std::uint64_t>(delta));
        return unwrapped_;
    }

    bool initialized() const noexcept { return initialized_; }
    std::int64_t value() const noexcept { return unwrapped_; }
    std::uint64_t modulus() const noexcept { return modulus_; }

private:
    std::uint64_t modulus_ = 0;
    std::int64_t last_raw_ = 0;
    std::int64_t unwrapped_ = 0;
    bool initialized_ = false;
};

class PeriodUnwrapper {
public:
    // period: the span after which the reported value repeats (e.g. 1.0 turn); 0 means "never wraps".
    explicit PeriodUnwrapper(double period = 0.0) noexcept : period_(period) {}

    void set_period(double period) noexcept {
        period_ = period;
        reset();
    }
    void reset() noexcept {
        initialized_ = false;
        turns_ = 0;
    }

    double update(double wrapped) noexcept {
        if (initialized_ && period_ > 0.0) {
            const double delta = wrapped - last_;
            if (delta > 0.5 * period_) --turns_;
            else if (delta < -0.5 * period_) ++turns_;
        }
        initialized_ = true;
        last_ = wrapped;
        // Whole turns kept as an integer: adding k * period fresh each time does not accumulate error.
        return wrapped + static_cast<double>(turns_) * period_;
    }

    bool initialized() const noexcept { return initialized_; }
    std::int64_t turns() const noexcept { return turns_; }

private:
    double period_ = 0.0;
    double last_ = 0.0;
    std::int64_t turns_ = 0;
    bool initialized_ = false;
};

}  // namespace jacobid::hal
