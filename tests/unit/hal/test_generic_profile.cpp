// SPDX-License-Identifier: MIT
// Generic signals: id, byte offset, bit width, signedness, byte order, scale and offset.
#include <gtest/gtest.h>

#include "hal_test_util.hpp"
#include "jacobid/hal/profiles/generic.hpp"

namespace {

using namespace jacobid::hal;
using jacobid::hal::test::frame;
using jacobid::hal::test::hex;

// Position: id 0x321, bytes 2..4, 24-bit signed big-endian, 2^20 counts per motor revolution.
// Torque: id 0x321, bytes 0..1, 16-bit signed little-endian, 0.01 N.m per count.
generic::JointConfig sensor() {
    generic::JointConfig c;
    c.position = {0x321, false, 2, 24, 0, true, ByteOrder::BigEndian, kTwoPi / 1048576.0, 0.0};
    c.effort = {0x321, false, 0, 16, 0, true, ByteOrder::LittleEndian, 0.01, 0.0};
    c.mapping.gear_ratio = 4.0;
    return c;
}

TEST(HalGeneric, ExtractsFieldsInEitherByteOrderAndSign) {
    // 2C 01 | 10 00 00: torque 0x012C = 300 -> 3.00 N.m; position 0x100000 = 2^20 = one turn.
    const CanFrame f = frame(0x321, {0x2C, 0x01, 0x10, 0x00, 0x00});
    const generic::JointConfig c = sensor();
    std::int64_t raw = 0;
    ASSERT_EQ(generic::extract_raw(c.effort, f, raw), DecodeStatus::Ok);
    EXPECT_EQ(raw, 300);
    ASSERT_EQ(generic::extract_raw(c.position, f, raw), DecodeStatus::Ok);
    EXPECT_EQ(raw, 0x100000);
    // FF FE ... : LE 0xFEFF = -257; BE 24-bit FF FF FE = -2.
    const CanFrame g = frame(0x321, {0xFF, 0xFE, 0xFF, 0xFF, 0xFE});
    ASSERT_EQ(generic::extract_raw(c.effort, g, raw), DecodeStatus::Ok);
    EXPECT_EQ(raw, -257);
    ASSERT_EQ(generic::extract_raw(c.position, g, raw), DecodeStatus::Ok);
    EXPECT_EQ(raw, -2);
    generic::Signal u = c.position;
    u.is_signed = false;
    ASSERT_EQ(generic::extract_raw(u, g, raw), DecodeStatus::Ok);
    EXPECT_EQ(raw, 0xFFFFFE);
}

TEST(HalGeneric, ShiftedFieldReadsTheMitVelocityNibbles) {
    // MIT reply bytes 3..4 = 12 3A: the velocity is the top 12 bits, 0x123.
    const generic::Signal v{0x000, false, 3, 12, 4, false, ByteOrder::BigEndian, 1.0, 0.0};
    std::int64_t raw = 0;
    ASSERT_EQ(generic::extract_raw(v, frame(0x000, {0x03, 0x12, 0x34, 0x12, 0x3A, 0xBC}), raw), DecodeStatus::Ok);
    EXPECT_EQ(raw, 0x123);
    CanFrame f = frame(0x000, {0x03, 0x12, 0x34, 0x00, 0x0A, 0xBC});
    generic::insert_raw(v, 0x123, f);  // must keep the low nibble 0xA of byte 4 (the torque's)
    EXPECT_EQ(hex(f), "03 12 34 12 3A BC");
}

TEST(HalGeneric, DecodesAJointThroughScaleOffsetAndRatio) {
    generic::JointDecoder d;
    generic::JointConfig c = sensor();
    c.effort.offset = -0.5;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    ASSERT_EQ(d.decode(frame(0x321, {0x2C, 0x01, 0x10, 0x00, 0x00}), s), DecodeStatus::Ok);
    EXPECT_NEAR(s.position, kTwoPi / 4.0, 1e-12);         // one motor turn / N
    EXPECT_NEAR(s.torque, (3.0 - 0.5) * 4.0, 1e-12);      // (raw * scale + offset) * N
    EXPECT_TRUE(s.fresh());
}

TEST(HalGeneric, UnwrapsAtTheFieldWidth) {
    generic::JointDecoder d;
    ASSERT_EQ(d.configure(sensor()), ConfigStatus::Ok);
    JointState s;
    ASSERT_EQ(d.decode(frame(0x321, {0, 0, 0x7F, 0xFF, 0xFF}), s), DecodeStatus::Ok);  // +8388607
    const double before = s.position;
    ASSERT_EQ(d.decode(frame(0x321, {0, 0, 0x80, 0x00, 0x00}), s), DecodeStatus::Ok);  // -8388608 = +1 count
    EXPECT_NEAR(s.position - before, kTwoPi / 1048576.0 / 4.0, 1e-12);
}

TEST(HalGeneric, RoundTripOnSeparateFramesOverManyTurns) {
    generic::JointConfig c;
    c.position = {0x18FF0010, true, 0, 16, 0, false, ByteOrder::LittleEndian, kTwoPi / 4096.0, 0.0};  // 12 bits/turn in 16
    c.effort = {0x18FF0011, true, 4, 32, 0, true, ByteOrder::BigEndian, 1e-3, 0.0};                    // mA
    c.effort_kind = EffortKind::Current;
    c.mapping.gear_ratio = 50.0;
    c.mapping.torque_constant = 0.08;
    generic::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    for (int k = 0; k <= 3000; ++k) {
        const double q = 2.0 * k * 1e-3;  // 6 rad link = 300 rad motor, 3 wraps of the 16-bit field
        const double tau = -3.0 + 2e-3 * k;
        CanFrame p;
        p.id = c.position.can_id;
        p.flags = kCanExtended;
        CanFrame e = p;
        e.id = c.effort.can_id;
        generic::encode_fields(c, q, 0.0, tau, p);
        generic::encode_fields(c, q, 0.0, tau, e);
        ASSERT_EQ(d.decode(p, s), DecodeStatus::Ok);
        ASSERT_EQ(d.decode(e, s), DecodeStatus::Ok);
        ASSERT_NEAR(s.position, q, 0.5 * kTwoPi / 4096.0 / 50.0 + 1e-12);
        ASSERT_NEAR(s.torque, tau, 0.5 * 1e-3 * 0.08 * 50.0 + 1e-12);
    }
}

TEST(HalGeneric, RejectsShortAndOutOfRangeFields) {
    generic::JointConfig c = sensor();
    c.effort.check_raw_range = true;
    c.effort.raw_min = -2000;
    c.effort.raw_max = 2000;
    generic::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    EXPECT_EQ(d.decode(frame(0x321, {0x2C, 0x01, 0x10, 0x00}), s), DecodeStatus::Short);
    EXPECT_EQ(d.decode(frame(0x321, {0x00, 0x80, 0x10, 0x00, 0x00}), s), DecodeStatus::OutOfRange);  // -32768
    EXPECT_EQ(d.decode(frame(0x322, {0x2C, 0x01, 0x10, 0x00, 0x00}), s), DecodeStatus::NotMine);
    EXPECT_FALSE(s.position_fresh);  // the position of a rejected frame is not used either
    EXPECT_EQ(s.position, 0.0);
}

TEST(HalGeneric, ValidatesLayouts) {
    generic::Signal sig{0x1, false, 0, 0, 0, true, ByteOrder::LittleEndian, 1.0, 0.0};
    EXPECT_EQ(generic::validate(sig), ConfigStatus::InvalidLayout);  // width 0
    sig.bit_width = 64;
    sig.bit_shift = 1;
    EXPECT_EQ(generic::validate(sig), ConfigStatus::InvalidLayout);  // 9 bytes
    sig.bit_shift = 0;
    EXPECT_EQ(generic::validate(sig), ConfigStatus::Ok);
    sig.byte_offset = 60;
    EXPECT_EQ(generic::validate(sig), ConfigStatus::InvalidLayout);
    sig.byte_offset = 0;
    sig.scale = 0.0;
    EXPECT_EQ(generic::validate(sig), ConfigStatus::InvalidScale);
    generic::JointConfig c = sensor();
    c.position.bit_width = 40;  // cannot unwrap beyond 32 bits
    EXPECT_EQ(generic::validate(c), ConfigStatus::InvalidLayout);
}

// Fuzzing (fuzz/targets/fuzz_profile_generic.cpp): a finite field times a large (valid) scale overflows.
TEST(HalGeneric, FuzzRegressionOverflowingScaleIsOutOfRangeAndChangesNothing) {
    generic::JointConfig c = sensor();
    c.position.scale = 1e305;
    c.effort.scale = 1e305;
    generic::JointDecoder d;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    JointState s;
    // Torque 1 count = 1e305 N.m, 4e305 on the link, is finite; 0x7FFF counts are inf.
    ASSERT_EQ(d.decode(frame(0x321, {0x01, 0x00, 0x00, 0x00, 0x00}), s), DecodeStatus::Ok);
    EXPECT_DOUBLE_EQ(s.torque, 4e305);
    const double torque = s.torque;
    EXPECT_EQ(d.decode(frame(0x321, {0xFF, 0x7F, 0x00, 0x00, 0x00}), s), DecodeStatus::OutOfRange);
    EXPECT_EQ(s.torque, torque);
    // Position 0x7FFFFF counts x 1e305 rad is inf as well.
    c.effort.scale = 0.01;
    ASSERT_EQ(d.configure(c), ConfigStatus::Ok);
    EXPECT_EQ(d.decode(frame(0x321, {0x00, 0x00, 0x7F, 0xFF, 0xFF}), s), DecodeStatus::OutOfRange);
    EXPECT_EQ(s.torque, torque);
    // A classic frame cannot carry more than 8 bytes.
    CanFrame f = frame(0x321, {0x00, 0x00, 0x00, 0x00, 0x00});
    f.len = 9;
    EXPECT_EQ(d.decode(f, s), DecodeStatus::Malformed);
}

}  // namespace
