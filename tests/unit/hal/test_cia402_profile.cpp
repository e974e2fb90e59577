// SPDX-License-Identifier: MIT
// CiA 402 TPDO: 0x6064 position (INT32 LE) with 0x6078 current or 0x6077 torque (INT16 LE, per mille).
#include <gtest/gtest.h>

#include <cmath>

#include "hal_test_util.hpp"
#include "jacobid/hal/profiles/cia402.hpp"

namespace {

using namespace jacobid::hal;
using jacobid::hal::test::frame;
using jacobid::hal::test::hex;

cia402::JointConfig drive(std::uint8_t node) {
    cia402::JointConfig c;
    c.node_id = node;
    c.counts_per_revolution = 10000.0;
    c.rated_current = 2.0;  // A
    c.rated_torque = 0.5;   // N.m
    c.mapping.gear_ratio = 100.0;
    c.mapping.torque_constant = 0.1;  // N.m/A
    return c;
}

// Node 5, TPDO1 -> COB-ID 0x180 + 5 = 0x185. Position 100000 = 0x000186A0 -> A0 86 01 00 (LE);
// current 500 per mille = 0x01F4 -> F4 01.
const CanFrame kTpdo = frame(0x185, {0xA0, 0x86, 0x01, 0x00, 0xF4, 0x01});

TEST(HalCia402, CobIdsOfThePredefinedConnectionSet) {
    EXPECT_EQ(cia402::tpdo_cob_id(1, 5), 0x185u);
    EXPECT_EQ(cia402::tpdo_cob_id(2, 5), 0x285u);
    EXPECT_EQ(cia402::tpdo_cob_id(4, 127), 0x4FFu);
    EXPECT_EQ(drive(5).cob_id(), 0x185u);
}

TEST(HalCia402, DecodesPositionAndCurrentFromAHandWrittenTpdo) {
    cia402::JointDecoder d;
    ASSERT_EQ(d.configure(drive(5)), ConfigStatus::Ok);
    JointState s;
    ASSERT_EQ(d.decode(kTpdo, s), DecodeStatus::Ok);
    // 100000 counts / 10000 per rev = 10 motor turns = 20 pi rad; link = / 100.
    EXPECT_NEAR(s.position, 10.0 * kTwoPi / 100.0, 1e-12);
    // 500 per mille of 2 A = 1 A; link torque = Kt * I * N = 0.1 * 1 * 100 = 10 N.m.
    EXPECT_NEAR(s.torque, 10.0, 1e-12);
    EXPECT_TRUE(s.fresh());
}

TEST(HalCia402, NegativeValuesAndTorqueActual) {
    cia402::JointConfig c = drive(5);
    c.layout.effort = cia402::EffortObject::TorqueActual;
    cia402::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    // Position -1 = FF FF FF FF; torque -250 per mille = 0xFF06 -> 06 FF.
    ASSERT_EQ(d.decode(frame(0x185, {0xFF, 0xFF, 0xFF, 0xFF, 0x06, 0xFF}), s), DecodeStatus::Ok);
    EXPECT_NEAR(s.position, -kTwoPi / 10000.0 / 100.0, 1e-15);
    EXPECT_NEAR(s.torque, -0.25 * 0.5 * 100.0, 1e-12);  // per mille * rated torque * N
}

TEST(HalCia402, EncodesTheSameBytesAsWrittenByHand) {
    CanFrame f;
    cia402::encode_tpdo(drive(5), 10.0 * kTwoPi / 100.0, 10.0, f);
    EXPECT_EQ(f.id, 0x185u);
    EXPECT_EQ(hex(f), hex(kTpdo));
}

TEST(HalCia402, UnwrapsTheInt32PositionAtItsLimits) {
    cia402::JointDecoder d;
    ASSERT_EQ(d.configure(drive(5)), ConfigStatus::Ok);
    JointState s;
    ASSERT_EQ(d.decode(frame(0x185, {0xFF, 0xFF, 0xFF, 0x7F, 0, 0}), s), DecodeStatus::Ok);  // INT32_MAX
    const double before = s.position;
    ASSERT_EQ(d.decode(frame(0x185, {0x00, 0x00, 0x00, 0x80, 0, 0}), s), DecodeStatus::Ok);  // INT32_MIN
    EXPECT_NEAR(s.position - before, kTwoPi / 10000.0 / 100.0, 1e-9);  // one count forward
}

TEST(HalCia402, ModuloPositionRangeRoundTripsOverManyTurns) {
    cia402::JointConfig c = drive(9);
    c.position_modulus = 10000;  // 0x607B range 0..9999: wraps every motor revolution
    c.mapping.gear_ratio = 7.0;
    cia402::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    for (int k = 0; k <= 5000; ++k) {
        const double q = 30.0 * std::sin(1e-3 * k);  // link rad: about 33 motor turns each way
        CanFrame f;
        cia402::encode_tpdo(c, q, 0.0, f);
        ASSERT_EQ(d.decode(f, s), DecodeStatus::Ok);
        ASSERT_NEAR(s.position, q, 0.5 * kTwoPi / 10000.0 / 7.0 + 1e-12) << "k " << k;
    }
    // A count beyond the modulo range cannot come from the drive.
    EXPECT_EQ(d.decode(frame(c.cob_id(), {0x10, 0x27, 0x00, 0x00, 0, 0}), s), DecodeStatus::OutOfRange);  // 10000
}

TEST(HalCia402, RejectsShortOutOfRangeAndForeignFrames) {
    cia402::JointDecoder d;
    ASSERT_EQ(d.configure(drive(5)), ConfigStatus::Ok);
    JointState s;
    EXPECT_EQ(d.decode(frame(0x185, {0xA0, 0x86, 0x01, 0x00, 0xF4}), s), DecodeStatus::Short);
    EXPECT_EQ(d.decode(frame(0x185, {0xA0, 0x86, 0x01}), s), DecodeStatus::Short);
    // 0x8000 = -32768 per mille: 33 x the rating, beyond the 10000 per mille limit.
    EXPECT_EQ(d.decode(frame(0x185, {0xA0, 0x86, 0x01, 0x00, 0x00, 0x80}), s), DecodeStatus::OutOfRange);
    EXPECT_EQ(d.decode(frame(0x186, {0xA0, 0x86, 0x01, 0x00, 0xF4, 0x01}), s), DecodeStatus::NotMine);
    EXPECT_EQ(d.decode(frame(0x185, {}, kCanRemote), s), DecodeStatus::Malformed);
    EXPECT_FALSE(s.position_fresh);
    EXPECT_EQ(s.position, 0.0);
}

TEST(HalCia402, ConfiguredLayoutAndPositionOnlyPdo) {
    cia402::JointConfig c = drive(5);
    c.layout.cob_id = cia402::tpdo_cob_id(2, 5);
    c.layout.effort = cia402::EffortObject::None;
    c.layout.position_byte = 2;  // e.g. statusword 0x6041 in bytes 0..1
    cia402::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    ASSERT_EQ(d.decode(frame(0x285, {0x37, 0x02, 0x10, 0x27, 0x00, 0x00}), s), DecodeStatus::Ok);  // 10000 counts
    EXPECT_NEAR(s.position, kTwoPi / 100.0, 1e-12);
    EXPECT_TRUE(s.position_fresh);
    EXPECT_FALSE(s.torque_fresh);
    EXPECT_EQ(d.decode(kTpdo, s), DecodeStatus::NotMine);  // 0x185 is not configured any more
}

TEST(HalCia402, ValidatesConfiguration) {
    cia402::JointConfig c = drive(0);
    EXPECT_EQ(cia402::validate(c), ConfigStatus::InvalidNodeId);
    c = drive(5);
    c.counts_per_revolution = 0.0;
    EXPECT_EQ(cia402::validate(c), ConfigStatus::InvalidScale);
    c = drive(5);
    c.rated_current = 0.0;
    EXPECT_EQ(cia402::validate(c), ConfigStatus::InvalidScale);
    c = drive(5);
    c.layout.effort_byte = 7;
    EXPECT_EQ(cia402::validate(c), ConfigStatus::InvalidLayout);
}

// Fuzzing (fuzz/targets/fuzz_profile_cia402.cpp) found this; the frame is the fuzzer's bytes.
TEST(HalCia402, FuzzRegressionOverflowingTorqueConstantIsOutOfRangeNotInfinite) {
    cia402::JointConfig c = drive(0x14);  // COB-ID 0x194
    c.mapping.gear_ratio = 1.0;
    c.mapping.torque_constant = 1.7976857124591637e+308;
    c.max_abs_per_mille = 32767;
    cia402::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    // -17734 per mille of 2 A times Kt = 1.8e308 N.m/A is -inf N.m.
    EXPECT_EQ(d.decode(frame(0x194, {0xBA, 0xBA, 0xBA, 0xBA, 0xBA, 0xBA}), s), DecodeStatus::OutOfRange);
    EXPECT_EQ(s.torque, 0.0);
    EXPECT_FALSE(s.position_fresh);
}

TEST(HalCia402, FuzzRegressionPositionOverflowIsRejectedWithoutMovingTheUnwrapper) {
    cia402::JointConfig c = drive(5);
    c.layout.effort = cia402::EffortObject::None;
    c.counts_per_revolution = 1e-310;  // finite and non-zero, but counts / it overflow
    cia402::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    EXPECT_EQ(d.decode(frame(0x185, {0x01, 0x00, 0x00, 0x00}), s), DecodeStatus::OutOfRange);
    EXPECT_FALSE(s.position_fresh);
    EXPECT_EQ(d.decode(frame(0x185, {0x00, 0x00, 0x00, 0x00}), s), DecodeStatus::Ok);  // 0 counts: 0 rad
    EXPECT_EQ(s.position, 0.0);
}

}  // namespace
