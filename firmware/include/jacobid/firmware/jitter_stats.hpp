// SPDX-License-Identifier: MIT
#pragma once
// Wake-up latency statistics of a periodic loop, as cyclictest reports them: min, average, max and a
// percentile in microseconds. A fixed histogram of 1 us bins (plus one overflow bin) gives the percentile
// without storing samples, so add() never allocates and costs a few instructions per cycle.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace jacobid::firmware {

class JitterStats {
public:
    static constexpr std::size_t kBins = 10000;  // 0 .. 9999 us; later samples land in the overflow bin

    void add(std::int64_t latency_ns) noexcept {
        if (latency_ns < 0) latency_ns = 0;  // woke early (cannot with TIMER_ABSTIME, but be safe)
        ++count_;
        sum_ns_ += static_cast<double>(latency_ns);
        min_ns_ = std::min(min_ns_, latency_ns);
        max_ns_ = std::max(max_ns_, latency_ns);
        const std::int64_t us = latency_ns / 1000;
        if (us >= static_cast<std::int64_t>(kBins)) ++overflow_;
        else ++bins_[static_cast<std::size_t>(us)];
    }
    void reset() noexcept { *this = JitterStats{}; }

    std::uint64_t count() const noexcept { return count_; }
    double min_us() const noexcept { return count_ ? static_cast<double>(min_ns_) / 1e3 : 0.0; }
    double max_us() const noexcept { return count_ ? static_cast<double>(max_ns_) / 1e3 : 0.0; }
    double avg_us() const noexcept { return count_ ? sum_ns_ / static_cast<double>(count_) / 1e3 : 0.0; }
    // Upper edge of the bin holding the p-quantile (p in (0, 1]): "p of the cycles woke within this many
    // us"; the max when the quantile is in the overflow bin.
    double percentile_us(double p) const noexcept {
        if (count_ == 0) return 0.0;
        const auto rank = static_cast<std::uint64_t>(std::max(1.0, p * static_cast<double>(count_) + 0.5 - 1e-9));
        std::uint64_t seen = 0;
        for (std::size_t i = 0; i < kBins; ++i) {
            seen += bins_[i];
            if (seen >= rank) return std::min(static_cast<double>(i + 1), max_us());
        }
        return max_us();
    }
    std::uint64_t overflow() const noexcept { return overflow_; }

private:
    std::array<std::uint32_t, kBins> bins_{};
    std::uint64_t overflow_ = 0;
    std::uint64_t count_ = 0;
    double sum_ns_ = 0.0;
    std::int64_t min_ns_ = std::numeric_limits<std::int64_t>::max();
    std::int64_t max_ns_ = 0;
};

}  // namespace jacobid::firmware
