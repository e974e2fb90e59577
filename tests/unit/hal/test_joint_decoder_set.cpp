// SPDX-License-Identifier: MIT
// The per-cycle demultiplexer: several profiles on one bus, counters by rejection reason, fresh/stale
// ageing, the simulator -> virtual bus -> decoder path, and zero allocation on the decode path.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "allocation_counter.hpp"
#include "hal_test_util.hpp"
#include "jacobid/hal/joint_decoder_set.hpp"
#include "jacobid/hal/virtual_can_bus.hpp"

namespace {

using namespace jacobid::hal;
using jacobid::hal::test::frame;

mit::JointConfig mit_joint(std::uint8_t motor) {
    mit::JointConfig c;
    c.motor_id = motor;
    c.mapping.gear_ratio = 1.0;
    return c;
}

odrive::JointConfig odrive_joint(std::uint8_t node) {
    odrive::JointConfig c;
    c.node_id = node;
    c.mapping.torque_constant = 0.05;
    c.mapping.gear_ratio = 10.0;
    return c;
}

cia402::JointConfig cia_joint(std::uint8_t node) {
    cia402::JointConfig c;
    c.node_id = node;
    c.counts_per_revolution = 4096.0;
    c.rated_current = 3.0;
    c.mapping.torque_constant = 0.2;
    c.mapping.gear_ratio = 50.0;
    return c;
}

// Joints: MIT motors 1 and 2 (both reply on id 0), ODrive node 3, CiA 402 node 5.
std::array<ProfileConfig, 4> robot() { return {mit_joint(1), mit_joint(2), odrive_joint(3), cia_joint(5)}; }

TEST(HalDecoderSet, RoutesEachFrameToItsJoint) {
    JointDecoderSet<8> set;
    const auto cfg = robot();
    ASSERT_EQ(set.configure(cfg).status, ConfigStatus::Ok);
    EXPECT_EQ(set.joint_count(), 4u);
    set.begin_cycle();
    // MIT motor 2 at code 0xFFFF (12.5 rad); motor 1 at code 0x0000 (-12.5 rad).
    EXPECT_EQ(set.dispatch(frame(0x000, {0x02, 0xFF, 0xFF, 0x80, 0x08, 0x00})), DecodeStatus::Ok);
    EXPECT_EQ(set.dispatch(frame(0x000, {0x01, 0x00, 0x00, 0x80, 0x08, 0x00})), DecodeStatus::Ok);
    EXPECT_DOUBLE_EQ(set.state(1).position, 12.5);
    EXPECT_DOUBLE_EQ(set.state(0).position, -12.5);
    // CiA node 5: 4096 counts = 1 turn (00 10 00 00), 0 current.
    EXPECT_EQ(set.dispatch(frame(0x185, {0x00, 0x10, 0x00, 0x00, 0x00, 0x00})), DecodeStatus::Ok);
    EXPECT_NEAR(set.state(3).position, kTwoPi / 50.0, 1e-12);
    EXPECT_EQ(set.counters().decoded, 3u);
    EXPECT_FALSE(set.state(2).position_fresh);
}

TEST(HalDecoderSet, CountsRejectionsByReasonAndFlagsTheJoint) {
    JointDecoderSet<8> set;
    const auto cfg = robot();
    ASSERT_EQ(set.configure(cfg).status, ConfigStatus::Ok);
    set.begin_cycle();
    EXPECT_EQ(set.dispatch(frame(0x000, {0x09, 0, 0, 0, 0, 0})), DecodeStatus::UnknownId);   // MIT motor 9
    EXPECT_EQ(set.dispatch(frame(0x123, {1, 2, 3})), DecodeStatus::UnknownId);              // nobody's id
    EXPECT_EQ(set.dispatch(frame(0x000, {0x02, 0xFF, 0xFF})), DecodeStatus::Short);         // motor 2, 3 bytes
    EXPECT_EQ(set.dispatch(frame(0x069, {0, 0, 0xC0, 0x7F, 0, 0, 0, 0})), DecodeStatus::OutOfRange);  // NaN
    EXPECT_EQ(set.dispatch(frame(0x185, {}, kCanRemote)), DecodeStatus::Malformed);
    const DecodeCounters& c = set.counters();
    EXPECT_EQ(c.frames, 5u);
    EXPECT_EQ(c.decoded, 0u);
    EXPECT_EQ(c.rejected_unknown_id, 2u);
    EXPECT_EQ(c.rejected_short, 1u);
    EXPECT_EQ(c.rejected_out_of_range, 1u);
    EXPECT_EQ(c.rejected_malformed, 1u);
    EXPECT_FALSE(set.state(0).decode_error);
    EXPECT_TRUE(set.state(1).decode_error);
    EXPECT_TRUE(set.state(2).decode_error);
    EXPECT_TRUE(set.state(3).decode_error);
    set.begin_cycle();
    EXPECT_FALSE(set.state(1).decode_error);  // per cycle
}

TEST(HalDecoderSet, FreshAndStaleFollowTheCycles) {
    JointDecoderSet<2> set;
    const std::array<ProfileConfig, 1> cfg = {odrive_joint(3)};
    ASSERT_EQ(set.configure(cfg, 2).status, ConfigStatus::Ok);  // stale after 2 cycles without data
    CanFrame enc, iq;
    odrive::encode_encoder_estimates(odrive_joint(3), 0.1, 0.0, enc);
    odrive::encode_iq(odrive_joint(3), 1.0, iq);
    set.begin_cycle();
    EXPECT_TRUE(set.state(0).stale);  // never seen
    set.dispatch(enc);
    EXPECT_TRUE(set.state(0).position_fresh);
    EXPECT_FALSE(set.state(0).fresh());
    EXPECT_TRUE(set.state(0).stale);  // torque never seen yet
    set.dispatch(iq);
    EXPECT_TRUE(set.state(0).fresh());
    EXPECT_FALSE(set.state(0).stale);
    for (int k = 1; k <= 2; ++k) {
        set.begin_cycle();
        EXPECT_FALSE(set.state(0).position_fresh);
        EXPECT_FALSE(set.state(0).stale) << "cycle " << k;
        EXPECT_EQ(set.state(0).position_age, static_cast<std::uint32_t>(k));
    }
    set.begin_cycle();
    EXPECT_TRUE(set.state(0).stale);
    set.dispatch(enc);               // position alone does not clear it: torque is 3 cycles old
    EXPECT_TRUE(set.state(0).stale);
    set.dispatch(iq);
    EXPECT_FALSE(set.state(0).stale);
}

TEST(HalDecoderSet, RejectsBadConfigurationWithTheJointIndex) {
    JointDecoderSet<2> set;
    auto cfg = robot();
    EXPECT_EQ(set.configure(cfg).status, ConfigStatus::TooManyJoints);
    JointDecoderSet<8> big;
    std::get<odrive::JointConfig>(cfg[2]).mapping.torque_constant = 0.0;
    const DecoderSetConfigResult r = big.configure(cfg);
    EXPECT_EQ(r.status, ConfigStatus::InvalidTorqueConstant);
    EXPECT_EQ(r.joint, 2u);
    EXPECT_EQ(big.joint_count(), 0u);
}

TEST(HalDecoderSet, SimulatorToVirtualBusToDecoderLoop) {
    VirtualCanBus<2, 16> bus;
    auto* sim = bus.attach();
    const CanFilter mine[] = {exact_filter(0x000), exact_filter(0x069), exact_filter(0x074), exact_filter(0x185)};
    auto* fw = bus.attach({}, mine);
    ASSERT_TRUE(sim && fw);
    JointDecoderSet<4> set;
    const auto cfg = robot();
    ASSERT_EQ(set.configure(cfg).status, ConfigStatus::Ok);
    std::array<CanFrame, 16> rx{};
    for (int k = 0; k < 2000; ++k) {
        const double t = 1e-3 * k;
        const double q = 20.0 * std::sin(t);  // crosses the MIT range end (12.5 rad) several times
        const double tau = 2.0 * std::cos(t);
        bus.set_time_ns(static_cast<std::int64_t>(k) * 1000000);
        CanFrame f;
        mit::encode_reply(mit_joint(1), q, 0.0, tau, f);
        ASSERT_EQ(sim->send(f), CanStatus::Ok);
        mit::encode_reply(mit_joint(2), -q, 0.0, -tau, f);
        sim->send(f);
        odrive::encode_encoder_estimates(odrive_joint(3), q, 0.0, f);
        sim->send(f);
        odrive::encode_iq(odrive_joint(3), tau, f);
        sim->send(f);
        cia402::encode_tpdo(cia_joint(5), q, tau, f);
        sim->send(f);
        sim->send(frame(0x700 + 5, {0x05}));  // a heartbeat the kernel filter keeps away

        set.begin_cycle();
        const DrainResult r = fw->drain(rx);
        ASSERT_EQ(r.count, 5u);
        set.dispatch(jacobid::Span<const CanFrame>(rx.data(), r.count));
        for (std::size_t j = 0; j < 4; ++j) ASSERT_TRUE(set.state(j).fresh()) << j;
        ASSERT_NEAR(set.state(0).position, q, 2e-4);
        ASSERT_NEAR(set.state(1).position, -q, 2e-4);
        ASSERT_NEAR(set.state(2).position, q, 1e-5);
        ASSERT_NEAR(set.state(3).position, q, kTwoPi / 4096.0 / 50.0);
        ASSERT_NEAR(set.state(0).torque, tau, 36.0 / 4095.0);
        ASSERT_NEAR(set.state(3).torque, tau, 0.2 * 3.0e-3 * 50.0);
        ASSERT_EQ(set.state(2).position_time_ns, static_cast<std::int64_t>(k) * 1000000);
    }
    EXPECT_EQ(set.counters().decoded, 2000u * 5u);
    EXPECT_EQ(set.counters().rejected_unknown_id, 0u);
    EXPECT_EQ(fw->counters().rx_overflows, 0u);
}

// route() names the joint whose own decode() took the frame: the firmware's duplicate detection uses it
// and has no test of its own that could drift from the decoders' (docs/profiles.md).
TEST(HalDecoderSet, RouteAttributesAFrameOnlyByTheDecodersOwnTest) {
    JointDecoderSet<8> set;
    const auto cfg = robot();  // MIT motors 1, 2 on id 0; ODrive node 3; CiA 402 node 5
    ASSERT_EQ(set.configure(cfg).status, ConfigStatus::Ok);
    set.begin_cycle();
    // A zero-length frame on the MIT reply id: MIT's decode cannot read data[0] and takes it (Short) for
    // the first motor on the id; no other joint is named.
    const RouteResult empty = set.route(frame(0x000, {}));
    EXPECT_EQ(empty.status, DecodeStatus::Short);
    EXPECT_EQ(empty.joint, 0u);
    // A standard frame whose id has bits above the 11-bit mask, with node 3 and Get_Encoder_Estimates in
    // its low bits: ODrive's decode rejects it, so no joint is named.
    const RouteResult wide = set.route(frame(0x800 | 0x069, {0x00, 0x00, 0xC0, 0x3F, 0x00, 0x00, 0x00, 0xC0}));
    EXPECT_EQ(wide.status, DecodeStatus::UnknownId);
    EXPECT_EQ(wide.joint, RouteResult::kNoJoint);
    EXPECT_FALSE(set.state(2).decode_error);
    // The same payload on the real id is node 3's.
    const RouteResult ok = set.route(frame(0x069, {0x00, 0x00, 0xC0, 0x3F, 0x00, 0x00, 0x00, 0xC0}));
    EXPECT_EQ(ok.status, DecodeStatus::Ok);
    EXPECT_EQ(ok.joint, 2u);
}

TEST(HalDecoderSet, RegistryTelemetryRoundTripsEveryProfile) {
    generic::JointConfig g;
    g.position.can_id = 0x280;
    g.position.bit_width = 32;
    g.position.scale = 1e-4;
    g.has_velocity = true;
    g.velocity.can_id = 0x281;
    g.velocity.scale = 1e-3;
    g.effort.can_id = 0x280;
    g.effort.byte_offset = 4;
    g.effort.scale = 1e-3;
    const std::array<ProfileConfig, 5> joints = {mit_joint(1), mit_joint(2), odrive_joint(3), cia_joint(5), g};
    JointDecoderSet<8> set;
    ASSERT_EQ(set.configure(joints).status, ConfigStatus::Ok);
    set.begin_cycle();
    std::array<CanFrame, kMaxTelemetryFrames> out{};
    for (std::size_t j = 0; j < joints.size(); ++j) {
        const std::size_t n = encode_telemetry(joints[j], 0.5, 0.25, 1.0, out.data());
        ASSERT_GE(n, 1u);
        for (std::size_t i = 0; i < n; ++i) {
            const RouteResult r = set.route(out[i]);
            EXPECT_EQ(r.status, DecodeStatus::Ok) << profile_name(joints[j]);
            EXPECT_EQ(r.joint, j) << profile_name(joints[j]);
        }
        EXPECT_TRUE(set.state(j).fresh()) << profile_name(joints[j]);
        EXPECT_NEAR(set.state(j).position, 0.5, 2e-3) << profile_name(joints[j]);
    }
}

TEST(HalDecoderSet, DecodePathAllocatesNothing) {
    JointDecoderSet<8> set;
    const auto cfg = robot();
    ASSERT_EQ(set.configure(cfg).status, ConfigStatus::Ok);
    VirtualCanBus<2, 64> bus;
    auto* sim = bus.attach();
    auto* fw = bus.attach();
    std::array<CanFrame, 64> rx{};
    std::size_t decoded = 0;
    const std::uint64_t before = jacobid::test::allocation_count();
    for (int k = 0; k < 5000; ++k) {
        const double q = 0.01 * k;
        CanFrame f;
        mit::encode_reply(mit_joint(1), q, 0.0, 1.0, f);
        sim->send(f);
        odrive::encode_encoder_estimates(odrive_joint(3), q, 0.0, f);
        sim->send(f);
        odrive::encode_iq(odrive_joint(3), 0.5, f);
        sim->send(f);
        cia402::encode_tpdo(cia_joint(5), q, 1.0, f);
        sim->send(f);
        sim->send(frame(0x000, {0x01, 0x00}));  // short: rejected path too
        sim->send(frame(0x3FF, {}));            // unknown id
        set.begin_cycle();
        const DrainResult r = fw->drain(rx);
        decoded += set.dispatch(jacobid::Span<const CanFrame>(rx.data(), r.count));
    }
    const std::uint64_t after = jacobid::test::allocation_count();
    EXPECT_EQ(after - before, 0u);
    EXPECT_EQ(decoded, 5000u * 4u);
    EXPECT_EQ(set.counters().rejected_short, 5000u);
    EXPECT_EQ(set.counters().rejected_unknown_id, 5000u);
}

}  // namespace
