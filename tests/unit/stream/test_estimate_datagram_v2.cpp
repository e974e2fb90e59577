// SPDX-License-Identifier: MIT
// Estimate datagram version 2 (the contact monitor's fields; docs/stream-format.md, "Version 2") against a
// datagram written by hand from the spec's table: version 1's header and joint blocks unchanged, each joint
// block followed by tau_ext (f64), the contact flags. Bit patterns worked out on paper, not captured from encode().
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "datagram_bytes.hpp"
#include "jacobid/stream/estimate_datagram.hpp"

namespace {

namespace st = jacobid::stream;
using st::DatagramStatus;
using jacobid::test::Bytes;
using Datagram = st::EstimateDatagram<4>;

using jacobid::test::bits_of;
using jacobid::test::from_hex;

// Two joints; stream flags contact | restart = 6; joint 2 in contact (flag 0x10).
//   1.0 = 3FF0000000000000   0.5 = 3FE0000000000000   -2.0 = C000000000000000   3.0 = 4008000000000000
//  10.0 = 4024000000000000  0.25 = 3FD0000000000000 -0.125 = BFC0000000000000  -1.0 = BFF0000000000000
// 0.001 = 3F50624DD2F1A9FC  -20.5 = C034800000000000
const char* kReferenceHex =
    // header: magic "JDST", version 2, 2 joints, flags 6, delay 25 samples
    "4A 44 53 54  02 00  02 00  06 00 00 00  19 00 00 00"
    // sequence 7, sample index 1000 (0x3E8)
    "07 00 00 00 00 00 00 00  E8 03 00 00 00 00 00 00"
    // time stamp 1000000 ns (0xF4240), sample period 0.001 s
    "40 42 0F 00 00 00 00 00  FC A9 F1 D2 4D 62 50 3F"
    // joint 1: q 1.0, q^ 0.5, qd^ -2.0, qdd^ 3.0, tau 10.0, flags 0, tau_ext 0.25
    "00 00 00 00 00 00 F0 3F  00 00 00 00 00 00 E0 3F  00 00 00 00 00 00 00 C0"
    "00 00 00 00 00 00 08 40  00 00 00 00 00 00 24 40  00 00 00 00"
    "00 00 00 00 00 00 D0 3F"
    // joint 2: q 0.25, q^ -0.125, qd^ 0.0, qdd^ -1.0, tau 3.0, flags contact = 0x10, tau_ext -20.5
    "00 00 00 00 00 00 D0 3F  00 00 00 00 00 00 C0 BF  00 00 00 00 00 00 00 00"
    "00 00 00 00 00 00 F0 BF  00 00 00 00 00 00 08 40  10 00 00 00"
    "00 00 00 00 00 80 34 C0";

Datagram reference_datagram() {
    Datagram d;
    d.version = st::kDatagramVersionMonitor;
    d.flags = st::kStreamContact | st::kStreamRestart;
    d.delay_samples = 25;
    d.sequence = 7;
    d.sample_index = 1000;
    d.timestamp_ns = 1000000;
    d.sample_period = 0.001;
    d.joint_count = 2;
    d.joints[0] = {1.0, 0.5, -2.0, 3.0, 10.0, 0, 0.25};
    d.joints[1] = {0.25, -0.125, 0.0, -1.0, 3.0, st::kJointContact, -20.5};
    return d;
}

Bytes encode_ok(const Datagram& d) {
    Bytes out(st::kMaxUdpPayload);
    std::size_t written = 0;
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(out), written), DatagramStatus::Ok);
    out.resize(written);
    return out;
}

DatagramStatus decode_bytes(const Bytes& b, Datagram& d) { return st::decode(jacobid::Span<const std::uint8_t>(b.data(), b.size()), d); }

TEST(EstimateDatagramV2, LayoutConstantsMatchTheSpec) {
    EXPECT_EQ(st::kDatagramVersionMonitor, 2u);
    EXPECT_EQ(st::kDatagramJointSizeMonitor, 52u);
    EXPECT_EQ(st::datagram_size(2, st::kDatagramVersionMonitor), 152u);
    EXPECT_EQ(st::datagram_size(2), 136u);  // version 1 is unchanged
    EXPECT_EQ(st::kProtocolMaxJointsMonitor, 1258u);
    EXPECT_LE(st::datagram_size(st::kProtocolMaxJointsMonitor, st::kDatagramVersionMonitor), st::kMaxUdpPayload);
    EXPECT_GT(st::datagram_size(st::kProtocolMaxJointsMonitor + 1, st::kDatagramVersionMonitor), st::kMaxUdpPayload);
}

TEST(EstimateDatagramV2, EncodeWritesTheHandWrittenBytes) {
    const Bytes expected = from_hex(kReferenceHex);
    ASSERT_EQ(expected.size(), 152u);
    EXPECT_EQ(encode_ok(reference_datagram()), expected);
}

TEST(EstimateDatagramV2, DecodeReadsTheHandWrittenBytes) {
    Datagram d;
    ASSERT_EQ(decode_bytes(from_hex(kReferenceHex), d), DatagramStatus::Ok);
    EXPECT_EQ(d.version, 2u);
    EXPECT_EQ(d.flags, st::kStreamContact | st::kStreamRestart);
    EXPECT_EQ(d.delay_samples, 25u);
    EXPECT_EQ(d.sequence, 7u);
    EXPECT_EQ(d.timestamp_ns, 1000000);
    ASSERT_EQ(d.joint_count, 2u);
    EXPECT_EQ(bits_of(d.joints[0].tau), bits_of(10.0));
    EXPECT_EQ(bits_of(d.joints[0].tau_ext), bits_of(0.25));
    EXPECT_EQ(d.joints[1].flags, st::kJointContact);
    EXPECT_EQ(bits_of(d.joints[1].qdd_hat), bits_of(-1.0));
    EXPECT_EQ(bits_of(d.joints[1].tau_ext), bits_of(-20.5));
}

// An old (version-1) receiver's checks on a version-2 datagram: the version field says 2, so it refuses it
// by version before reading a joint block; it never reads 52-byte blocks as 44-byte ones.
TEST(EstimateDatagramV2, VersionOneFieldsSitWhereVersionOneHasThem) {
    const Bytes v2 = from_hex(kReferenceHex);
    Datagram v1 = reference_datagram();
    v1.version = st::kDatagramVersion;
    v1.flags = st::kStreamRestart;
    v1.joints[1].flags = 0;
    const Bytes old = encode_ok(v1);
    // The header (but for version and flags) and each joint's first 40 bytes are the same bytes.
    EXPECT_TRUE(std::equal(old.begin() + 12, old.begin() + 48, v2.begin() + 12));
    for (std::size_t j = 0; j < 2; ++j) {
        EXPECT_TRUE(std::equal(old.begin() + 48 + 44 * j, old.begin() + 48 + 44 * j + 40, v2.begin() + 48 + 52 * j));
    }
    EXPECT_EQ(st::wire::get_u16(v2.data() + 4), 2u);
}

TEST(EstimateDatagramV2, ContactFlagsAreVersionTwoOnly) {
    Datagram d = reference_datagram();
    d.version = st::kDatagramVersion;
    Bytes out(st::kMaxUdpPayload);
    std::size_t written = 0;
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(out), written), DatagramStatus::UnknownFlags);
    // A version-1 datagram whose stream flags carry the contact bit is refused by the decoder too.
    Bytes bytes = encode_ok([] {
        Datagram v1 = reference_datagram();
        v1.version = st::kDatagramVersion;
        v1.flags = 0;
        v1.joints[1].flags = 0;
        return v1;
    }());
    bytes[8] = 4;
    Datagram back;
    EXPECT_EQ(decode_bytes(bytes, back), DatagramStatus::UnknownFlags);
}

TEST(EstimateDatagramV2, NonFiniteExternalTorqueOnlyOnAFlaggedJoint) {
    Datagram d = reference_datagram();
    d.joints[0].tau_ext = std::numeric_limits<double>::quiet_NaN();
    Bytes out(st::kMaxUdpPayload);
    std::size_t written = 0;
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(out), written), DatagramStatus::NonFiniteEstimate);
    // The contact bit does not excuse it: contact means a valid, large estimate.
    d.joints[0].flags = st::kJointContact;
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(out), written), DatagramStatus::NonFiniteEstimate);
    d.joints[0].flags = st::kJointWarmup;
    EXPECT_EQ(st::encode(d, jacobid::Span<std::uint8_t>(out), written), DatagramStatus::Ok);
}

TEST(EstimateDatagramV2, SizeFollowsTheVersion) {
    Bytes bytes = from_hex(kReferenceHex);
    Datagram d;
    bytes.pop_back();
    EXPECT_EQ(decode_bytes(bytes, d), DatagramStatus::Truncated);
    bytes.push_back(0xC0);
    bytes.push_back(0x00);
    EXPECT_EQ(decode_bytes(bytes, d), DatagramStatus::Oversized);
    bytes = from_hex(kReferenceHex);
    bytes[4] = 3;
    EXPECT_EQ(decode_bytes(bytes, d), DatagramStatus::UnsupportedVersion);
}

}  // namespace
