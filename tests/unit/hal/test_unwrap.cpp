// SPDX-License-Identifier: MIT
// Multi-turn unwrapping on integer counts and on a floating-point period.
#include <gtest/gtest.h>

#include <cstdint>

#include "jacobid/hal/unwrap.hpp"

namespace {

using jacobid::hal::CountUnwrapper;
using jacobid::hal::PeriodUnwrapper;

TEST(HalUnwrap, SixteenBitCodeCrossesTheWrapBothWays) {
    CountUnwrapper u(1u << 16);
    EXPECT_EQ(u.update(0xFFFE), 0xFFFE);
    EXPECT_EQ(u.update(0xFFFF), 0xFFFF);
    EXPECT_EQ(u.update(0x0000), 0x10000);  // one code further, not 65535 back
    EXPECT_EQ(u.update(0x0001), 0x10001);
    EXPECT_EQ(u.update(0xFFFF), 0xFFFF);   // and back over the boundary
    EXPECT_EQ(u.update(0xFFF0), 0xFFF0);
}

TEST(HalUnwrap, ManyTurnsStayExactOnCounts) {
    // 200 turns forward then back, 1000 counts per step, on a 2^16 code: the unwrapped count must equal
    // the true count exactly at every step.
    CountUnwrapper u(1u << 16);
    std::int64_t truth = 12345;
    u.update(truth & 0xFFFF);
    for (int dir : {1, -1}) {
        for (int i = 0; i < 200 * 66; ++i) {
            truth += dir * 1000;
            const std::int64_t wrapped = ((truth % 65536) + 65536) % 65536;
            ASSERT_EQ(u.update(wrapped), truth) << "step " << i;
        }
    }
}

TEST(HalUnwrap, SignedInt32WrapsAtTheLimits) {
    CountUnwrapper u(1ull << 32);
    EXPECT_EQ(u.update(-5), -5);  // the first sample keeps its sign
    EXPECT_EQ(u.update(7), 7);
    CountUnwrapper v(1ull << 32);
    v.update(INT32_MAX - 1);
    EXPECT_EQ(v.update(INT32_MAX), static_cast<std::int64_t>(INT32_MAX));
    EXPECT_EQ(v.update(INT32_MIN), static_cast<std::int64_t>(INT32_MAX) + 1);
    EXPECT_EQ(v.update(INT32_MIN + 10), static_cast<std::int64_t>(INT32_MAX) + 11);
}

// A field that never wraps (modulus 0) jumping across the whole int64 range (a corrupt 64-bit field, found by
// fuzz_profile_generic): the difference wraps modulo 2^64 instead of overflowing (undefined behaviour), so
// the unwrapped value follows the raw one.
TEST(HalUnwrap, NonWrappingFieldAcrossTheWholeInt64Range) {
    CountUnwrapper u(0);
    EXPECT_EQ(u.update(INT64_MIN), INT64_MIN);
    EXPECT_EQ(u.update(INT64_MAX), INT64_MAX);
    EXPECT_EQ(u.update(INT64_MIN), INT64_MIN);
    EXPECT_EQ(u.update(-3), -3);
}

TEST(HalUnwrap, ModulusThatIsNotAPowerOfTwo) {
    CountUnwrapper u(10000);  // a single-turn encoder, 10000 counts per revolution
    u.update(9990);
    EXPECT_EQ(u.update(5), 10005);
    EXPECT_EQ(u.update(9995), 9995);
    EXPECT_EQ(u.update(4000), 14000);  // +4005: less than half a period
    EXPECT_EQ(u.update(9000), 9000);   // +5000 is exactly half: taken as -5000
}

TEST(HalUnwrap, PeriodUnwrapperCountsTurns) {
    PeriodUnwrapper u(1.0);
    EXPECT_DOUBLE_EQ(u.update(0.9), 0.9);
    EXPECT_DOUBLE_EQ(u.update(0.05), 1.05);
    EXPECT_DOUBLE_EQ(u.update(0.95), 0.95);
    EXPECT_DOUBLE_EQ(u.update(0.2), 1.2);
    EXPECT_EQ(u.turns(), 1);
    PeriodUnwrapper none(0.0);
    none.update(0.9);
    EXPECT_DOUBLE_EQ(none.update(0.05), 0.05);  // period 0: never wraps
}

}  // namespace
