// SPDX-License-Identifier: MIT
// Estimate datagram (lib/include/jacobid/stream/estimate_datagram.hpp) against the byte layout of
// docs/stream-format.md. The reference datagram below is written by hand from the spec's table (offsets,
// little-endian, IEEE-754 bit patterns worked out on paper), not captured from encode().
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "allocation_counter.hpp"
#include "datagram_bytes.hpp"
#include "jacobid/stream/estimate_datagram.hpp"

namespace {

namespace st = jacobid::stream;
using st::DatagramStatus;
using jacobid::test::Bytes;
using Datagram = st::EstimateDatagram<4>;

using jacobid::test::bits_of;
using jacobid::test::from_hex;

// Two joints, e-stop set. Joint 1 clean; joint 2 stale + warm-up with q = NaN (allowed by those flags).
//   1.0 = 3FF0000000000000   0.5 = 3FE0000000000000   -2.0 = C000000000000000   3.0 = 4008000000000000
//  10.0 = 4024000000000000  0.25 = 3FD0000000000000 -0.125 = BFC0000000000000  -1.0 = BFF0000000000000
// 0.001 = 3F50624DD2F1A9FC   NaN = 7FF8000000000000 (quiet NaN)
const char* kReferenceHex =
    // header: magic "JDST", version 1, 2 joints, flags = e-stop, delay 100 samples
    "4A 44 53 54  01 00  02 00  01 00 00 00  64 00 00 00"
    // sequence 0x0102030405060708, sample index 1000 (0x3E8)
    "08 07 06 05 04 03 02 01  E8 03 00 00 00 00 00 00"
    // time stamp 0x17A2B3C4D5E6F708 ns, sample period 0.001 s
    "08 F7 E6 D5 C4 B3 A2 17  FC A9 F1 D2 4D 62 50 3F"
    // joint 1: q 1.0, q^ 0.5, qd^ -2.0, qdd^ 3.0, tau 10.0, flags 0
    "00 00 00 00 00 00 F0 3F  00 00 00 00 00 00 E0 3F  00 00 00 00 00 00 00 C0"
    "00 00 00 00 00 00 08 40  00 00 00 00 00 00 24 40  00 00 00 00"
    // joint 2: q NaN, q^ 0.25, qd^ -0.125, qdd^ 0.0, tau -1.0, flags stale | warm-up = 5
    "00 00 00 00 00 00 F8 7F  00 00 00 00 00 00 D0 3F  00 00 00 00 00 00 C0 BF"
    "00 00 00 00 00 00 00 00  00 00 00 00 00 00 F0 BF  05 00 00 00";

Datagram reference_datagram() {
    Datagram d;
    d.flags = st::kStreamEstop;
    d.delay_samples = 100;
    d.sequence = 0x0102030405060708ull;
    d.sample_index = 1000;
    d.timestamp_ns = 0x17A2B3C4D5E6F708ll;
    d.sample_period = 0.001;
    d.joint_count = 2;
    d.joints[0] = {1.0, 0.5, -2.0, 3.0, 10.0, 0};
    d.joints[1] = {std::numeric_limits<double>::quiet_NaN(), 0.25, -0.125, 0.0, -1.0, st::kJointStale | st::kJointWarmup};
    return d;
}

// Bit-exact comparison (NaN == NaN, -0 != +0), joint by joint.
void expect_same(const Datagram& a, const Datagram& b) {
    EXPECT_EQ(a.flags, b.flags);
    EXPECT_EQ(a.delay_samples, b.delay_samples);
    EXPECT_EQ(a.sequence, b.sequence);
    EXPECT_EQ(a.sample_index, b.sample_index);
    EXPECT_EQ(a.timestamp_ns, b.timestamp_ns);
    EXPECT_EQ(bits_of(a.sample_period), bits_of(b.sample_period));
    ASSERT_EQ(a.joint_count, b.joint_count);
    for (std::size_t j = 0; j < a.joint_count; ++j) {
        SCOPED_TRACE("joint " + std::to_string(j));
        EXPECT_EQ(bits_of(a.joints[j].q), bits_of(b.joints[j].q));
        EXPECT_EQ(bits_of(a.joints[j].q_hat), bits_of(b.joints[j].q_hat));
        EXPECT_EQ(bits_of(a.joints[j].qd_hat), bits_of(b.joints[j].qd_hat));
        EXPECT_EQ(bits_of(a.joints[j].qdd_hat), bits_of(b.joints[j].qdd_hat));
        EXPECT_EQ(bits_of(a.joints[j].tau), bits_of(b.joints[j].tau));
        EXPECT_EQ(a.joints[j].flags, b.joints[j].flags);
    }
}

DatagramStatus decode_bytes(const Bytes& b, Datagram& d) { return st::decode(jacobid::Span<const std::uint8_t>(b.data(), b.size()), d); }

DatagramStatus decode_bytes(const Bytes& b) {
    Datagram d;
    return decode_bytes(b, d);
}

Bytes encode_ok(const Datagram& d) {
    Bytes out(st::kMaxUdpPayload);
    std::size_t written = 0;
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(out), written), DatagramStatus::Ok);
    out.resize(written);
    return out;
}

void put_f64_at(Bytes& b, std::size_t offset, double v) {
    const std::uint64_t bits = bits_of(v);
    for (int i = 0; i < 8; ++i) b[offset + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(bits >> (8 * i));
}

TEST(EstimateDatagram, LayoutConstantsMatchTheSpec) {
    EXPECT_EQ(st::kDatagramHeaderSize, 48u);
    EXPECT_EQ(st::kDatagramJointSize, 44u);
    EXPECT_EQ(st::datagram_size(2), 136u);
    EXPECT_EQ(st::kProtocolMaxJoints, 1487u);
    EXPECT_LE(st::datagram_size(st::kProtocolMaxJoints), st::kMaxUdpPayload);
    EXPECT_GT(st::datagram_size(st::kProtocolMaxJoints + 1), st::kMaxUdpPayload);
}

TEST(EstimateDatagram, DecodesTheHandWrittenReference) {
    const Bytes bytes = from_hex(kReferenceHex);
    ASSERT_EQ(bytes.size(), 136u);
    Datagram d;
    ASSERT_EQ(decode_bytes(bytes, d), DatagramStatus::Ok);
    EXPECT_EQ(d.sequence, 0x0102030405060708ull);
    EXPECT_EQ(d.sample_index, 1000u);
    EXPECT_EQ(d.delay_samples, 100u);
    EXPECT_EQ(d.timestamp_ns, 1703121267083114248ll);  // 0x17A2B3C4D5E6F708 in decimal
    EXPECT_EQ(d.sample_period, 0.001);
    EXPECT_EQ(d.flags, st::kStreamEstop);
    ASSERT_EQ(d.joint_count, 2u);
    EXPECT_EQ(d.joints[0].q, 1.0);
    EXPECT_EQ(d.joints[0].q_hat, 0.5);
    EXPECT_EQ(d.joints[0].qd_hat, -2.0);
    EXPECT_EQ(d.joints[0].qdd_hat, 3.0);
    EXPECT_EQ(d.joints[0].tau, 10.0);
    EXPECT_EQ(d.joints[0].flags, 0u);
    EXPECT_TRUE(std::isnan(d.joints[1].q));
    EXPECT_EQ(d.joints[1].q_hat, 0.25);
    EXPECT_EQ(d.joints[1].qd_hat, -0.125);
    EXPECT_EQ(d.joints[1].qdd_hat, 0.0);
    EXPECT_EQ(d.joints[1].tau, -1.0);
    EXPECT_EQ(d.joints[1].flags, 5u);
    expect_same(d, reference_datagram());
}

TEST(EstimateDatagram, EncodesTheHandWrittenReferenceByteForByte) {
    const Bytes expected = from_hex(kReferenceHex);
    const Bytes actual = encode_ok(reference_datagram());
    ASSERT_EQ(actual.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(actual[i], expected[i]) << "byte " << i;
}

TEST(EstimateDatagram, NegativeTimeStampIsTwosComplement) {
    Datagram d = reference_datagram();
    d.timestamp_ns = -2;  // FE FF FF FF FF FF FF FF
    const Bytes b = encode_ok(d);
    for (std::size_t i = 32; i < 40; ++i) EXPECT_EQ(b[i], i == 32 ? 0xFE : 0xFF);
    Datagram back;
    ASSERT_EQ(decode_bytes(b, back), DatagramStatus::Ok);
    EXPECT_EQ(back.timestamp_ns, -2);
}

TEST(EstimateDatagram, RoundTripsRandomDatagramsBitExactly) {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> value(-1e3, 1e3);
    const double specials[] = {0.0, -0.0, std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max(),
                               -std::numeric_limits<double>::lowest(), 1e-300};
    for (int trial = 0; trial < 500; ++trial) {
        Datagram d;
        d.joint_count = 1 + rng() % 4;
        d.flags = static_cast<std::uint32_t>(rng() % 4);
        d.delay_samples = static_cast<std::uint32_t>(rng());
        d.sequence = rng();
        d.sample_index = rng();
        d.timestamp_ns = static_cast<std::int64_t>(rng());
        d.sample_period = std::abs(value(rng)) + 1e-9;
        for (std::size_t j = 0; j < d.joint_count; ++j) {
            auto pick = [&] { return rng() % 8 == 0 ? specials[rng() % 6] : value(rng); };
            d.joints[j] = {pick(), pick(), pick(), pick(), pick(), static_cast<std::uint32_t>(rng() % 16)};
        }
        const Bytes b = encode_ok(d);
        ASSERT_EQ(b.size(), st::datagram_size(d.joint_count));
        Datagram back;
        ASSERT_EQ(decode_bytes(b, back), DatagramStatus::Ok);
        expect_same(back, d);
    }
}

TEST(EstimateDatagram, RejectsEveryTruncation) {
    const Bytes full = from_hex(kReferenceHex);
    for (std::size_t n = 0; n < full.size(); ++n) {
        const Bytes cut(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(n));
        EXPECT_EQ(decode_bytes(cut), DatagramStatus::Truncated) << n << " bytes";
    }
}

TEST(EstimateDatagram, RejectsTrailingBytes) {
    Bytes b = from_hex(kReferenceHex);
    b.push_back(0);
    EXPECT_EQ(decode_bytes(b), DatagramStatus::Oversized);
}

TEST(EstimateDatagram, RejectsWrongMagicEvenWhenShort) {
    for (std::size_t i = 0; i < 4; ++i) {
        Bytes b = from_hex(kReferenceHex);
        b[i] ^= 0x20;  // "jDST", "JdST", ...
        EXPECT_EQ(decode_bytes(b), DatagramStatus::BadMagic) << "byte " << i;
    }
    EXPECT_EQ(decode_bytes(from_hex("4A 44 53 55 01 00")), DatagramStatus::BadMagic);
}

TEST(EstimateDatagram, RejectsOtherVersions) {
    // 2 is the monitor's version (test_estimate_datagram_v2.cpp): these bytes would be a truncated one.
    for (const int v : {0, 3, 255}) {
        Bytes b = from_hex(kReferenceHex);
        b[4] = static_cast<std::uint8_t>(v);
        EXPECT_EQ(decode_bytes(b), DatagramStatus::UnsupportedVersion) << v;
    }
    Bytes b = from_hex(kReferenceHex);
    b[5] = 1;  // version 0x0101: the high byte counts
    EXPECT_EQ(decode_bytes(b), DatagramStatus::UnsupportedVersion);
}

TEST(EstimateDatagram, RejectsZeroJointsAndJointsBeyondCapacity) {
    Bytes b = from_hex(kReferenceHex);
    b[6] = 0;
    b.resize(48);
    EXPECT_EQ(decode_bytes(b), DatagramStatus::NoJoints);

    st::EstimateDatagram<1> one;
    const Bytes two = from_hex(kReferenceHex);
    EXPECT_EQ(st::decode(jacobid::Span<const std::uint8_t>(two.data(), two.size()), one), DatagramStatus::TooManyJoints);

    // A count that claims more joints than the bytes hold is a truncation, not an overflow of the buffer.
    Bytes three = from_hex(kReferenceHex);
    three[6] = 3;
    EXPECT_EQ(decode_bytes(three), DatagramStatus::Truncated);
    // And fewer than the bytes hold leaves trailing bytes.
    Bytes one_joint = from_hex(kReferenceHex);
    one_joint[6] = 1;
    EXPECT_EQ(decode_bytes(one_joint), DatagramStatus::Oversized);
}

TEST(EstimateDatagram, RejectsUnknownFlagBits) {
    Bytes stream = from_hex(kReferenceHex);
    stream[8] |= 0x04;  // bit 2 of the stream flags: undefined in version 1
    EXPECT_EQ(decode_bytes(stream), DatagramStatus::UnknownFlags);
    Bytes stream_high = from_hex(kReferenceHex);
    stream_high[11] = 0x80;
    EXPECT_EQ(decode_bytes(stream_high), DatagramStatus::UnknownFlags);
    Bytes joint = from_hex(kReferenceHex);
    joint[48 + 40] = 0x10;  // joint 1, bit 4
    EXPECT_EQ(decode_bytes(joint), DatagramStatus::UnknownFlags);
}

TEST(EstimateDatagram, RejectsBadSamplePeriods) {
    // 1e300 s: found by fuzz_stream_recorder, sample index x period overflowed the recorder's time column.
    for (double ts : {0.0, -0.001, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 5e-10, 1000.5, 1e300}) {
        Bytes b = from_hex(kReferenceHex);
        put_f64_at(b, 40, ts);
        EXPECT_EQ(decode_bytes(b), DatagramStatus::InvalidSamplePeriod) << ts;
    }
    for (double ts : {1e-9, 1e-3, 1000.0}) {
        Bytes b = from_hex(kReferenceHex);
        put_f64_at(b, 40, ts);
        EXPECT_EQ(decode_bytes(b), DatagramStatus::Ok) << ts;
    }
}

TEST(EstimateDatagram, NonFiniteValuesOnlyWhereTheFlagsAllowThem) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const std::size_t j1 = 48, j2 = 48 + 44;
    struct Case {
        std::size_t offset;
        double value;
        std::uint32_t flags;  // written to the joint's flags
        DatagramStatus expected;
    };
    const Case cases[] = {
        {j1 + 0, nan, 0, DatagramStatus::NonFiniteMeasurement},           // q, clean joint
        {j1 + 32, -inf, 0, DatagramStatus::NonFiniteMeasurement},         // tau, clean joint
        {j1 + 0, nan, st::kJointWarmup, DatagramStatus::NonFiniteMeasurement},  // warm-up does not excuse q
        {j1 + 0, nan, st::kJointStale, DatagramStatus::Ok},
        {j1 + 32, nan, st::kJointDecodeError, DatagramStatus::Ok},
        {j1 + 8, nan, 0, DatagramStatus::NonFiniteEstimate},              // q^
        {j1 + 16, inf, 0, DatagramStatus::NonFiniteEstimate},             // qd^
        {j1 + 24, nan, 0, DatagramStatus::NonFiniteEstimate},             // qdd^
        {j1 + 16, nan, st::kJointWarmup, DatagramStatus::Ok},
        {j1 + 24, inf, st::kJointWindowStale, DatagramStatus::Ok},
        {j2 + 32, inf, st::kJointStale, DatagramStatus::Ok},
        {j2 + 0, nan, st::kJointWarmup, DatagramStatus::NonFiniteMeasurement},  // joint 2 without its stale bit
    };
    for (const Case& c : cases) {
        Bytes b = from_hex(kReferenceHex);
        put_f64_at(b, c.offset, c.value);
        const std::size_t flags_at = c.offset < j2 ? j1 + 40 : j2 + 40;
        b[flags_at] = static_cast<std::uint8_t>(c.flags);
        EXPECT_EQ(decode_bytes(b), c.expected) << "offset " << c.offset << " flags " << c.flags;
    }
}

TEST(EstimateDatagram, EncodeRejectsWhatDecodeWouldReject) {
    std::vector<std::uint8_t> buffer(st::kMaxUdpPayload);
    std::size_t written = 99;
    Datagram d = reference_datagram();
    d.joints[0].q = std::numeric_limits<double>::infinity();
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(buffer), written), DatagramStatus::NonFiniteMeasurement);
    EXPECT_EQ(written, 0u);
    d = reference_datagram();
    d.flags = 1u << 7;
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(buffer), written), DatagramStatus::UnknownFlags);
    d = reference_datagram();
    d.sample_period = 0.0;
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(buffer), written), DatagramStatus::InvalidSamplePeriod);
    d = reference_datagram();
    d.joint_count = 0;
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(buffer), written), DatagramStatus::NoJoints);
    d.joint_count = 5;
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(buffer), written), DatagramStatus::TooManyJoints);
    d = reference_datagram();
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(buffer.data(), 135), written), DatagramStatus::BufferTooSmall);
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(buffer.data(), 136), written), DatagramStatus::Ok);
    EXPECT_EQ(written, 136u);
}

TEST(EstimateDatagram, EveryStatusHasItsOwnDescription) {
    std::set<std::string> seen;
    for (int s = 0; s <= static_cast<int>(DatagramStatus::BufferTooSmall); ++s) {
        const std::string text = st::describe(static_cast<DatagramStatus>(s));
        EXPECT_FALSE(text.empty());
        EXPECT_NE(text, "unknown datagram status");
        EXPECT_TRUE(seen.insert(text).second) << text;
    }
}

TEST(EstimateDatagram, EncodeAndDecodeDoNotAllocate) {
    std::uint8_t buffer[st::datagram_size(4)];
    const Datagram d = reference_datagram();
    Datagram back;
    std::size_t written = 0;
    std::uint64_t sum = 0;
    const auto before = jacobid::test::allocation_count();
    for (int i = 0; i < 1000; ++i) {
        if (st::encode(d, jacobid::Span<std::uint8_t>(buffer), written) != DatagramStatus::Ok) break;
        if (st::decode(jacobid::Span<const std::uint8_t>(buffer, written), back) != DatagramStatus::Ok) break;
        sum += back.sequence;
    }
    const auto after = jacobid::test::allocation_count();
    EXPECT_EQ(after, before);
    EXPECT_EQ(sum, 1000 * d.sequence);
    // The counter does see allocations (so the zero above is not an artefact).
    const auto probe = jacobid::test::allocation_count();
    std::vector<int> v(16);
    EXPECT_GT(jacobid::test::allocation_count(), probe);
    EXPECT_EQ(v.size(), 16u);
}

}  // namespace
