// SPDX-License-Identifier: MIT
// CanFrame validity and the acceptance-filter semantics shared by the virtual bus and SocketCAN.
#include <gtest/gtest.h>

#include "hal_test_util.hpp"
#include "jacobid/hal/can_frame.hpp"

namespace {

using namespace jacobid::hal;
using jacobid::hal::test::frame;

TEST(HalCanFrame, FdLengthsAreTheElevenDlcCodesAboveEight) {
    // ISO 11898-1 FD: DLC 9..15 mean 12, 16, 20, 24, 32, 48, 64 bytes; nothing in between.
    int valid = 0;
    for (std::size_t len = 0; len <= 70; ++len) valid += is_valid_fd_length(len) ? 1 : 0;
    EXPECT_EQ(valid, 9 + 7);
    EXPECT_TRUE(is_valid_fd_length(48));
    EXPECT_FALSE(is_valid_fd_length(9));
    EXPECT_FALSE(is_valid_fd_length(63));
}

TEST(HalCanFrame, ValidityChecksIdWidthLengthAndFlags) {
    EXPECT_TRUE(is_valid_frame(frame(0x7FF, {1, 2, 3})));
    EXPECT_FALSE(is_valid_frame(frame(0x800, {1})));                       // 12 bits in a standard id
    EXPECT_TRUE(is_valid_frame(frame(0x1FFFFFFF, {1}, kCanExtended)));
    EXPECT_FALSE(is_valid_frame(frame(0x20000000, {1}, kCanExtended)));     // 30 bits
    CanFrame nine = frame(0x10, {1, 2, 3, 4, 5, 6, 7, 8, 9});
    EXPECT_FALSE(is_valid_frame(nine));                                      // classic: at most 8
    nine.flags = kCanFd;
    EXPECT_FALSE(is_valid_frame(nine));                                      // FD: 9 is not a length
    CanFrame twelve = frame(0x10, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}, kCanFd | kCanBitRateSwitch);
    EXPECT_TRUE(is_valid_frame(twelve));
    EXPECT_FALSE(is_valid_frame(frame(0x10, {}, kCanFd | kCanRemote)));    // FD has no RTR
    EXPECT_FALSE(is_valid_frame(frame(0x10, {}, kCanBitRateSwitch)));      // BRS on a classic frame
}

TEST(HalCanFrame, FilterMatchesIdUnderMaskAndFormat) {
    const CanFilter f{0x120, 0x7F0, CanIdFormat::Standard, false};  // 0x120..0x12F
    EXPECT_TRUE(matches(f, frame(0x120, {})));
    EXPECT_TRUE(matches(f, frame(0x12F, {})));
    EXPECT_FALSE(matches(f, frame(0x130, {})));
    EXPECT_FALSE(matches(f, frame(0x11F, {})));
    EXPECT_FALSE(matches(f, frame(0x120, {}, kCanExtended)));  // same number, other format
    EXPECT_FALSE(matches(f, frame(0x120, {}, kCanRemote)));    // remote refused by default
    CanFilter any = f;
    any.format = CanIdFormat::Any;
    any.accept_remote = true;
    EXPECT_TRUE(matches(any, frame(0x120, {}, kCanExtended)));
    EXPECT_TRUE(matches(any, frame(0x125, {}, kCanRemote)));
    const CanFilter exact = exact_filter(0x18FF0001, true);
    EXPECT_TRUE(matches(exact, frame(0x18FF0001, {}, kCanExtended)));
    EXPECT_FALSE(matches(exact, frame(0x18FF0002, {}, kCanExtended)));
}

TEST(HalCanFrame, EmptyFilterSetAcceptsEverythingAndAnySetIsAnOr) {
    const CanFilter set[] = {exact_filter(0x100), exact_filter(0x200)};
    EXPECT_TRUE(matches_any(set, 0, frame(0x333, {})));
    EXPECT_TRUE(matches_any(set, 2, frame(0x200, {})));
    EXPECT_FALSE(matches_any(set, 2, frame(0x300, {})));
    EXPECT_FALSE(matches_any(set, 1, frame(0x200, {})));
}

}  // namespace
