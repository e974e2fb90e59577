// SPDX-License-Identifier: MIT
// MIT-mode reply: byte-exact frames written from the layout in mit.hpp (mini-cheetah pack_reply), the
// AK80-9 ranges, demultiplexing on data[0], unwrapping at the range ends, rejection of bad frames.
#include <gtest/gtest.h>

#include <cmath>

#include "hal_test_util.hpp"
#include "jacobid/hal/profiles/mit.hpp"

namespace {

using namespace jacobid::hal;
using jacobid::hal::test::frame;
using jacobid::hal::test::hex;

mit::JointConfig ak80(std::uint8_t motor, double ratio = 1.0) {
    mit::JointConfig c;
    c.reply_can_id = 0x000;
    c.motor_id = motor;
    c.ranges = mit::kAk80_9;
    c.mapping.gear_ratio = ratio;
    return c;
}

// Frame A: motor 1, position code 0xFFFF (= p_max = 12.5 rad), velocity code 0x000 (= v_min = -50
// rad/s), torque code 0xFFF (= t_max = 18 N.m), temperature 0x41 = 65 -> 65 - 40 = 25 degC, error 0.
//   d[3] = v >> 4 = 0x00, d[4] = (v & 0xF) << 4 | t >> 8 = 0x0F, d[5] = t & 0xFF = 0xFF.
const CanFrame kFrameA = frame(0x000, {0x01, 0xFF, 0xFF, 0x00, 0x0F, 0xFF, 0x41, 0x00});
// Frame C: motor 3, position 0x1234, velocity 0x123, torque 0xABC, temperature 0x55 (45 degC), error 2.
//   d[3] = 0x12, d[4] = 0x3 << 4 | 0xA = 0x3A, d[5] = 0xBC.
const CanFrame kFrameC = frame(0x000, {0x03, 0x12, 0x34, 0x12, 0x3A, 0xBC, 0x55, 0x02});

TEST(HalMit, UnpacksTheFieldsOfHandWrittenFrames) {
    mit::RawReply r;
    ASSERT_EQ(mit::unpack_reply(kFrameC, r), DecodeStatus::Ok);
    EXPECT_EQ(r.motor_id, 3);
    EXPECT_EQ(r.position, 0x1234);
    EXPECT_EQ(r.velocity, 0x123);
    EXPECT_EQ(r.effort, 0xABC);
    EXPECT_TRUE(r.has_status);
    EXPECT_EQ(r.temperature, 0x55);
    EXPECT_EQ(r.error, 2);
    // Mini-cheetah 6-byte reply: motor 2, position 0x0000, velocity 0xFFF, torque 0x000.
    ASSERT_EQ(mit::unpack_reply(frame(0x000, {0x02, 0x00, 0x00, 0xFF, 0xF0, 0x00}), r), DecodeStatus::Ok);
    EXPECT_EQ(r.velocity, 0xFFF);
    EXPECT_EQ(r.effort, 0x000);
    EXPECT_FALSE(r.has_status);
}

TEST(HalMit, DecodesTheRangeEndsAndScalesThroughTheGearRatio) {
    mit::JointDecoder d;
    ASSERT_EQ(d.configure(ak80(1, 2.0)), ConfigStatus::Ok);  // an external 2:1 belt after the actuator
    JointState s;
    ASSERT_EQ(d.decode(kFrameA, s), DecodeStatus::Ok);
    EXPECT_DOUBLE_EQ(s.position, 12.5 / 2.0);  // link = motor / N
    EXPECT_DOUBLE_EQ(s.velocity, -50.0 / 2.0);
    EXPECT_DOUBLE_EQ(s.torque, 18.0 * 2.0);    // link = motor torque * N
    EXPECT_EQ(s.temperature_c, 25);
    EXPECT_EQ(s.device_error, 0);
    EXPECT_TRUE(s.fresh());
}

TEST(HalMit, DecodesMidRangeCodesWithTheLinearScale) {
    mit::JointDecoder d;
    ASSERT_EQ(d.configure(ak80(3)), ConfigStatus::Ok);
    JointState s;
    ASSERT_EQ(d.decode(kFrameC, s), DecodeStatus::Ok);
    EXPECT_NEAR(s.position, -12.5 + 0x1234 * 25.0 / 65535.0, 1e-12);
    EXPECT_NEAR(s.velocity, -50.0 + 0x123 * 100.0 / 4095.0, 1e-12);
    EXPECT_NEAR(s.torque, -18.0 + 0xABC * 36.0 / 4095.0, 1e-12);
    EXPECT_EQ(s.temperature_c, 45);
    EXPECT_EQ(s.device_error, 2);
}

TEST(HalMit, CurrentEffortUsesTheTorqueConstant) {
    mit::JointConfig c = ak80(1, 6.0);
    c.effort = EffortKind::Current;
    c.ranges.t_min = -40.0;
    c.ranges.t_max = 40.0;  // A
    c.mapping.torque_constant = 0.1;  // N.m/A
    mit::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    ASSERT_EQ(d.decode(kFrameA, s), DecodeStatus::Ok);  // effort code 0xFFF = 40 A
    EXPECT_DOUBLE_EQ(s.torque, 0.1 * 40.0 * 6.0);       // Kt * I * N
    c.mapping.torque_constant = 0.0;
    EXPECT_EQ(d.configure(c), ConfigStatus::InvalidTorqueConstant);
}

TEST(HalMit, EncodesTheSameBytesAsWrittenByHand) {
    CanFrame f;
    mit::encode_reply(ak80(1), 12.5, -50.0, 18.0, f, true, 25, 0);
    EXPECT_EQ(hex(f), hex(kFrameA));
    EXPECT_EQ(f.id, 0x000u);
    mit::encode_reply(ak80(2), -12.5, 50.0, -18.0, f, false);
    EXPECT_EQ(hex(f), "02 00 00 FF F0 00");
    // Saturation: velocity and torque beyond the range clamp to the end codes.
    mit::encode_reply(ak80(2), -12.5, 500.0, -180.0, f, false);
    EXPECT_EQ(hex(f), "02 00 00 FF F0 00");
}

TEST(HalMit, UnwrapsAcrossTheRangeEnd) {
    // Codes 0xFFFE, 0xFFFF, 0x0000, 0x0001: the motor keeps turning forward past +12.5 rad.
    mit::JointDecoder d;
    ASSERT_EQ(d.configure(ak80(1)), ConfigStatus::Ok);
    JointState s;
    const double step = 25.0 / 65535.0;
    double previous = 0.0;
    int i = 0;
    for (int code : {0xFFFE, 0xFFFF, 0x0000, 0x0001}) {
        CanFrame f = kFrameA;
        f.data[1] = static_cast<std::uint8_t>(code >> 8);
        f.data[2] = static_cast<std::uint8_t>(code & 0xFF);
        ASSERT_EQ(d.decode(f, s), DecodeStatus::Ok);
        if (i++ > 0) {
            EXPECT_NEAR(s.position - previous, step, 1e-12) << "code " << code;
        }
        previous = s.position;
    }
    EXPECT_NEAR(s.position, 12.5 + 2 * step, 1e-12);
}

TEST(HalMit, RoundTripOverManyTurnsWithinHalfACode) {
    // Link trajectory over +-40 turns of the actuator through a 3:1 reduction and reversed direction.
    mit::JointConfig c = ak80(7, 3.0);
    c.mapping.direction = -1.0;
    c.mapping.position_offset = 0.3;
    mit::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    const double half_code_link = 0.5 * 25.0 / 65535.0 / 3.0;
    for (int k = 0; k <= 4000; ++k) {
        const double t = k * 1e-3;
        const double q = 85.0 * std::sin(2.0 * 3.14159265358979 * 0.5 * t);  // about 40 actuator turns peak
        CanFrame f;
        mit::encode_reply(c, q, 1.0, 2.0, f);
        ASSERT_EQ(d.decode(f, s), DecodeStatus::Ok);
        ASSERT_NEAR(s.position, q, half_code_link * 1.0001) << "k " << k;
    }
}

TEST(HalMit, DemultiplexesOnTheMotorId) {
    mit::JointDecoder one, three;
    ASSERT_EQ(one.configure(ak80(1)), ConfigStatus::Ok);
    ASSERT_EQ(three.configure(ak80(3)), ConfigStatus::Ok);
    JointState s;
    EXPECT_EQ(one.decode(kFrameC, s), DecodeStatus::NotMine);
    EXPECT_EQ(three.decode(kFrameC, s), DecodeStatus::Ok);
    CanFrame other_id = kFrameC;
    other_id.id = 0x001;
    EXPECT_EQ(three.decode(other_id, s), DecodeStatus::NotMine);
    other_id = kFrameC;
    other_id.flags = kCanExtended;
    EXPECT_EQ(three.decode(other_id, s), DecodeStatus::NotMine);
}

TEST(HalMit, RejectsShortMalformedAndImplausibleFramesWithoutTouchingTheState) {
    mit::JointConfig c = ak80(1);
    c.require_status = true;
    c.mapping.max_abs_torque = 10.0;
    mit::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    s.position = 42.0;
    EXPECT_EQ(d.decode(frame(0x000, {0x01, 0x80, 0x00, 0x80, 0x08}), s), DecodeStatus::Short);     // 5 bytes
    EXPECT_EQ(d.decode(frame(0x000, {}), s), DecodeStatus::Short);                                  // no data[0]
    EXPECT_EQ(d.decode(frame(0x000, {0x01, 0x80, 0x00, 0x80, 0x08, 0x00}), s), DecodeStatus::Short);  // 6 < 8 required
    EXPECT_EQ(d.decode(frame(0x000, {}, kCanRemote), s), DecodeStatus::Malformed);
    EXPECT_EQ(d.decode(kFrameA, s), DecodeStatus::OutOfRange);  // 18 N.m > 10 N.m limit
    EXPECT_EQ(s.position, 42.0);
    EXPECT_FALSE(s.position_fresh);
}

TEST(HalMit, ValidatesConfiguration) {
    mit::JointConfig c = ak80(1);
    c.ranges.p_min = 12.5;
    EXPECT_EQ(mit::validate(c), ConfigStatus::InvalidRange);
    c = ak80(1);
    c.reply_can_id = 0x800;
    EXPECT_EQ(mit::validate(c), ConfigStatus::InvalidCanId);
    c = ak80(1, 0.0);
    EXPECT_EQ(mit::validate(c), ConfigStatus::InvalidGearRatio);
    // Issue 20: |N| within 1e-6..1e6, |offset| within 1e4 (a gear ratio of 1e308 was accepted).
    for (const double ratio : {1e308, -1e308, 1.0000001e6, 9.9e-7}) EXPECT_EQ(mit::validate(ak80(1, ratio)), ConfigStatus::GearRatioOutOfRange) << ratio;
    for (const double ratio : {1e6, -1e6, 1e-6, -1e-6}) EXPECT_EQ(mit::validate(ak80(1, ratio)), ConfigStatus::Ok) << ratio;
    c = ak80(1);
    c.mapping.position_offset = 1e308;
    EXPECT_EQ(mit::validate(c), ConfigStatus::InvalidOffset);
    c.mapping.position_offset = -1e4;
    EXPECT_EQ(mit::validate(c), ConfigStatus::Ok);
    c = ak80(1);
    c.mapping.direction = 0.5;
    EXPECT_EQ(mit::validate(c), ConfigStatus::InvalidDirection);
}

// Fuzzing (fuzz/targets/fuzz_profile_mit.cpp) found these; the frames are the fuzzer's bytes.
TEST(HalMit, FuzzRegressionOverflowingScaleIsOutOfRangeNotInfinite) {
    // The fuzzer's gear ratio -1.797e308 times 18 N.m was -inf: with the default infinite limits the old
    // check |tau| <= inf let it through as a decoded torque. Such a ratio is now refused at configuration
    // (issue 20: |N| within 1e-6..1e6); an effort range near the double's limit times the largest valid
    // ratio still overflows, and must still be OutOfRange.
    EXPECT_EQ(mit::validate(ak80(0xFF, -1.7976930280580734e+308)), ConfigStatus::GearRatioOutOfRange);
    mit::JointConfig c = ak80(0xFF, -1e6);
    c.ranges.t_min = -8e307;
    c.ranges.t_max = 8e307;
    c.reply_can_id = 0x73B;
    c.extended_id = true;
    c.mapping.direction = -1.0;
    mit::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    CanFrame f = frame(0x73B, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x00}, kCanExtended);
    EXPECT_EQ(d.decode(f, s), DecodeStatus::OutOfRange);
    EXPECT_EQ(s.torque, 0.0);
    EXPECT_FALSE(s.position_fresh || s.torque_fresh);
    // The same bytes with the length byte the fuzzer gave them (253): no transport delivers that.
    f.len = 253;
    EXPECT_EQ(d.decode(f, s), DecodeStatus::Malformed);
}

TEST(HalMit, FuzzRegressionRangeSpanMustBeFinite) {
    mit::JointConfig c = ak80(1);
    c.ranges.p_min = -1.7e308;
    c.ranges.p_max = 1.7e308;  // p_max - p_min overflows: every position would be inf or NaN
    EXPECT_EQ(mit::validate(c), ConfigStatus::InvalidRange);
}

TEST(HalMit, FuzzRegressionAnyTemperatureOffsetIsClampedWithoutOverflow) {
    mit::JointConfig c = ak80(1);
    c.temperature_offset = -2147483647 - 1;  // raw - offset overflowed int (UBSan), now clamps
    mit::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    ASSERT_EQ(d.decode(kFrameA, s), DecodeStatus::Ok);
    EXPECT_EQ(s.temperature_c, 32767);
}

}  // namespace
