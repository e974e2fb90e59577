// SPDX-License-Identifier: MIT
// ODrive CANSimple: 0x009 encoder estimates and 0x014 Iq, float32 little-endian, id = node << 5 | cmd.
#include <gtest/gtest.h>

#include "hal_test_util.hpp"
#include "jacobid/hal/profiles/odrive.hpp"

namespace {

using namespace jacobid::hal;
using jacobid::hal::test::frame;
using jacobid::hal::test::hex;

odrive::JointConfig axis(std::uint8_t node) {
    odrive::JointConfig c;
    c.node_id = node;
    c.mapping.gear_ratio = 10.0;
    c.mapping.torque_constant = 0.05;  // 8.27 / Kv
    return c;
}

// Node 3: 0x009 -> id 3 << 5 | 0x09 = 0x69. Pos 1.5 turns = 0x3FC00000 -> 00 00 C0 3F;
// vel -2.0 turns/s = 0xC0000000 -> 00 00 00 C0.
const CanFrame kEncoder = frame(0x069, {0x00, 0x00, 0xC0, 0x3F, 0x00, 0x00, 0x00, 0xC0});
// Node 3: 0x014 -> 0x60 | 0x14 = 0x74. Setpoint 2.0 A = 0x40000000 -> 00 00 00 40; measured 0.5 A =
// 0x3F000000 -> 00 00 00 3F.
const CanFrame kIq = frame(0x074, {0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x00, 0x3F});

TEST(HalOdrive, IdsComposeNodeAndCommand) {
    EXPECT_EQ(odrive::can_id(3, odrive::kGetEncoderEstimates), 0x069u);
    EXPECT_EQ(odrive::can_id(3, odrive::kGetIq), 0x074u);
    EXPECT_EQ(odrive::can_id(63, 0x1F), 0x7FFu);
    EXPECT_EQ(odrive::node_of(0x074), 3);
    EXPECT_EQ(odrive::command_of(0x074), 0x14);
}

TEST(HalOdrive, DecodesHandWrittenEncoderAndIqFrames) {
    odrive::JointDecoder d;
    ASSERT_EQ(d.configure(axis(3)), ConfigStatus::Ok);
    JointState s;
    ASSERT_EQ(d.decode(kEncoder, s), DecodeStatus::Ok);
    EXPECT_DOUBLE_EQ(s.position, 1.5 * kTwoPi / 10.0);
    EXPECT_DOUBLE_EQ(s.velocity, -2.0 * kTwoPi / 10.0);
    EXPECT_TRUE(s.position_fresh);
    EXPECT_FALSE(s.torque_fresh);  // torque comes in its own message
    ASSERT_EQ(d.decode(kIq, s), DecodeStatus::Ok);
    EXPECT_DOUBLE_EQ(s.torque, 0.05 * 0.5 * 10.0);  // Kt * Iq_measured * N, not the setpoint
    EXPECT_TRUE(s.fresh());
}

TEST(HalOdrive, EncodesTheSameBytesAsWrittenByHand) {
    CanFrame f;
    odrive::encode_encoder_estimates(axis(3), 1.5 * kTwoPi / 10.0, -2.0 * kTwoPi / 10.0, f);
    EXPECT_EQ(f.id, 0x069u);
    EXPECT_EQ(hex(f), hex(kEncoder));
    odrive::pack_iq(3, {2.0f, 0.5f}, f);
    EXPECT_EQ(f.id, 0x074u);
    EXPECT_EQ(hex(f), hex(kIq));
    odrive::encode_iq(axis(3), 0.05 * 0.5 * 10.0, f);
    EXPECT_EQ(hex(f), "00 00 00 3F 00 00 00 3F");  // setpoint reported = measured
}

TEST(HalOdrive, UnwrapsCircularPositions) {
    odrive::JointConfig c = axis(3);
    c.position_wrap_turns = 1.0;
    c.mapping.gear_ratio = 1.0;
    odrive::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    CanFrame f;
    for (float turns : {0.8f, 0.95f, 0.05f, 0.2f}) {
        odrive::pack_encoder_estimates(3, {turns, 1.0f}, f);
        ASSERT_EQ(d.decode(f, s), DecodeStatus::Ok);
    }
    EXPECT_NEAR(s.position, 1.2 * kTwoPi, 1e-6);
}

TEST(HalOdrive, RejectsShortNonFiniteAndForeignFrames) {
    odrive::JointConfig c = axis(3);
    c.mapping.max_abs_torque = 0.1;
    odrive::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    EXPECT_EQ(d.decode(frame(0x069, {0x00, 0x00, 0xC0, 0x3F, 0x00, 0x00, 0x00}), s), DecodeStatus::Short);
    // NaN (0x7FC00000) position: an uncalibrated axis or corruption.
    EXPECT_EQ(d.decode(frame(0x069, {0x00, 0x00, 0xC0, 0x7F, 0x00, 0x00, 0x00, 0x00}), s), DecodeStatus::OutOfRange);
    // +inf (0x7F800000) Iq.
    EXPECT_EQ(d.decode(frame(0x074, {0, 0, 0, 0, 0x00, 0x00, 0x80, 0x7F}), s), DecodeStatus::OutOfRange);
    EXPECT_EQ(d.decode(kIq, s), DecodeStatus::OutOfRange);  // 0.25 N.m > 0.1 N.m limit
    EXPECT_EQ(d.decode(frame(0x089, {0, 0, 0, 0, 0, 0, 0, 0}), s), DecodeStatus::NotMine);  // node 4
    EXPECT_EQ(d.decode(frame(0x061, {0, 0, 0, 0, 0, 0, 0, 0}), s), DecodeStatus::NotMine);  // node 3 heartbeat
    EXPECT_EQ(d.decode(frame(0x069, {}, kCanRemote), s), DecodeStatus::Malformed);        // the request itself
    EXPECT_FALSE(s.position_fresh);
    EXPECT_FALSE(s.torque_fresh);
    EXPECT_EQ(odrive::validate(axis(64)), ConfigStatus::InvalidNodeId);
}

// Fuzzing (fuzz/targets/fuzz_profile_odrive.cpp) found this; the frame is the fuzzer's bytes.
TEST(HalOdrive, FuzzRegressionOverflowingGearRatioIsOutOfRangeNotInfinite) {
    odrive::JointConfig c = axis(21);  // Iq of node 21: 21 << 5 | 0x14 = 0x2B4
    c.mapping.gear_ratio = -4.2133432848332276e+307;
    c.mapping.torque_constant = 0.083;
    // The fuzzer's gear ratio is now refused at configuration (issue 20: |N| within 1e-6..1e6); the largest
    // valid ratio with a torque constant near the double's limit still overflows the decoded torque.
    EXPECT_EQ(odrive::validate(c), ConfigStatus::GearRatioOutOfRange);
    c.mapping.gear_ratio = -1e6;
    c.mapping.torque_constant = 1e300;
    odrive::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    // Iq measured = float D7D7D7D7 = -4.7e14 A: times Kt and the gear ratio it overflows to inf.
    EXPECT_EQ(d.decode(frame(0x2B4, {0xD7, 0xD7, 0xD7, 0xD7, 0xD7, 0xD7, 0xD7, 0xD7}), s), DecodeStatus::OutOfRange);
    EXPECT_EQ(s.torque, 0.0);
    EXPECT_FALSE(s.torque_fresh);
}

}  // namespace
