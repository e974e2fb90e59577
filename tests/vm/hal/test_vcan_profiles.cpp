// SPDX-License-Identifier: MIT
// Every motor profile end to end over the kernel: frames encoded by the hal profile encoders (the
// simulator side) go through vcan to a SocketCanTransport with kernel filters (the firmware side) and
// are decoded by the JointDecoderSet, with the kernel receive time as the sample time (label vcan).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "jacobid/hal/joint_decoder_set.hpp"
#include "vcan_test_util.hpp"

namespace {

using namespace jacobid::hal;
using namespace jacobid::hal::vcan_test;

struct Tolerance {
    double position;
    double torque;
};

// One joint of each profile, with the resolution of its wire format.
struct ProfileCase {
    std::string name;
    ProfileConfig config;
    std::vector<CanFilter> filters;  // what the firmware lets through the kernel
    Tolerance tolerance;
};

mit::JointConfig mit_joint() {
    mit::JointConfig c;
    c.motor_id = 1;
    c.mapping.gear_ratio = 1.0;
    return c;
}
cia402::JointConfig cia_joint() {
    cia402::JointConfig c;
    c.node_id = 5;
    c.counts_per_revolution = 4096.0;
    c.rated_current = 3.0;
    c.mapping.torque_constant = 0.2;
    c.mapping.gear_ratio = 50.0;
    return c;
}
odrive::JointConfig odrive_joint() {
    odrive::JointConfig c;
    c.node_id = 3;
    c.mapping.torque_constant = 0.05;
    c.mapping.gear_ratio = 10.0;
    return c;
}
generic::JointConfig generic_joint() {
    generic::JointConfig c;  // 24-bit big-endian position, 2^20 counts per motor turn; 0.01 N.m torque
    c.position = {0x321, false, 2, 24, 0, true, ByteOrder::BigEndian, kTwoPi / 1048576.0, 0.0};
    c.effort = {0x321, false, 0, 16, 0, true, ByteOrder::LittleEndian, 0.01, 0.0};
    c.mapping.gear_ratio = 4.0;
    return c;
}

std::vector<ProfileCase> cases() {
    return {
        {"mit", mit_joint(), {exact_filter(0x000)}, {2e-4, 36.0 / 4095.0}},
        {"cia402", cia_joint(), {exact_filter(cia402::tpdo_cob_id(1, 5))}, {kTwoPi / 4096.0 / 50.0, 0.2 * 3.0e-3 * 50.0}},
        {"odrive", odrive_joint(), {exact_filter(odrive::can_id(3, odrive::kGetEncoderEstimates)),
                                    exact_filter(odrive::can_id(3, odrive::kGetIq))}, {1e-5, 1e-5}},
        {"generic", generic_joint(), {exact_filter(0x321)}, {kTwoPi / 1048576.0 / 4.0, 0.01 * 4.0}},
    };
}

// The frames the device would send for (q, tau) at one instant.
std::vector<CanFrame> encode(const ProfileConfig& config, double q, double tau) {
    std::vector<CanFrame> out;
    CanFrame f;
    if (const auto* m = std::get_if<mit::JointConfig>(&config)) {
        mit::encode_reply(*m, q, 0.0, tau, f);
        out.push_back(f);
    } else if (const auto* c = std::get_if<cia402::JointConfig>(&config)) {
        cia402::encode_tpdo(*c, q, tau, f);
        out.push_back(f);
    } else if (const auto* o = std::get_if<odrive::JointConfig>(&config)) {
        odrive::encode_encoder_estimates(*o, q, 0.0, f);
        out.push_back(f);
        odrive::encode_iq(*o, tau, f);
        out.push_back(f);
    } else if (const auto* g = std::get_if<generic::JointConfig>(&config)) {
        f = CanFrame{};
        f.id = g->position.can_id;
        f.len = 5;
        generic::encode_fields(*g, q, 0.0, tau, f);
        out.push_back(f);
    }
    return out;
}

class VcanProfile : public ::testing::TestWithParam<ProfileCase> {
protected:
    void SetUp() override { ASSERT_TRUE(interface_exists(can_interface())); }
};

TEST_P(VcanProfile, SimulatorToVcanToDecoderSet) {
    const ProfileCase& pc = GetParam();
    SocketCanTransport sim, fw;
    ASSERT_EQ(sim.open(config(can_interface())), CanStatus::Ok);
    ASSERT_EQ(fw.open(config(can_interface(), jacobid::Span<const CanFilter>(pc.filters.data(), pc.filters.size()))), CanStatus::Ok);
    JointDecoderSet<4> set;
    const std::array<ProfileConfig, 1> joints = {pc.config};
    ASSERT_EQ(set.configure(joints).status, ConfigStatus::Ok);

    std::array<CanFrame, 16> rx{};
    for (int k = 0; k < 400; ++k) {
        const double t = 5e-3 * k;
        const double q = 20.0 * std::sin(t);  // crosses the MIT range end (12.5 rad): unwrapping
        const double tau = 2.0 * std::cos(3.0 * t);
        const std::vector<CanFrame> frames = encode(pc.config, q, tau);
        for (const CanFrame& f : frames) ASSERT_EQ(sim.send(f), CanStatus::Ok);
        // Frames for others on the same bus: the kernel filter keeps them away from the firmware.
        ASSERT_EQ(sim.send(jacobid::hal::CanFrame{0x705, 1, 0, {0x05}, 0}), CanStatus::Ok);
        ASSERT_EQ(sim.send(jacobid::hal::CanFrame{0x1FF, 2, kCanExtended, {0x01, 0x02}, 0}), CanStatus::Ok);

        set.begin_cycle();
        const std::int64_t before_read = realtime_ns();
        const std::vector<CanFrame> got = receive_frames(fw, frames.size());
        ASSERT_EQ(got.size(), frames.size()) << "cycle " << k;
        std::copy(got.begin(), got.end(), rx.begin());
        ASSERT_EQ(set.dispatch(jacobid::Span<const CanFrame>(rx.data(), got.size())), got.size()) << "cycle " << k;
        const JointState& s = set.state(0);
        ASSERT_TRUE(s.fresh()) << "cycle " << k;
        ASSERT_NEAR(s.position, q, pc.tolerance.position) << "cycle " << k;
        ASSERT_NEAR(s.torque, tau, pc.tolerance.torque + 1e-9) << "cycle " << k;
        // The sample time is the kernel receive time of the frame, not our read time.
        ASSERT_GT(s.position_time_ns, 0);
        ASSERT_LE(s.position_time_ns, realtime_ns());
        ASSERT_GE(before_read + 1000000000LL, s.position_time_ns);
    }
    EXPECT_EQ(set.counters().rejected_unknown_id, 0u);
    EXPECT_EQ(set.counters().decoded, fw.counters().rx_frames);
    EXPECT_EQ(fw.counters().rx_overflows, 0u);
    CanFrame extra;
    EXPECT_EQ(fw.receive(extra), CanStatus::Empty);  // nothing of the other devices got through
}

INSTANTIATE_TEST_SUITE_P(Profiles, VcanProfile, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<ProfileCase>& p) { return p.param.name; });

TEST(VcanRobot, AllProfilesOnOneBusThroughOneFilteredSocket) {
    ASSERT_TRUE(interface_exists(can_interface()));
    std::vector<CanFilter> filters;
    std::array<ProfileConfig, 4> joints{};
    std::vector<Tolerance> tolerance;
    std::size_t j = 0;
    for (const ProfileCase& pc : cases()) {
        filters.insert(filters.end(), pc.filters.begin(), pc.filters.end());
        joints[j++] = pc.config;
        tolerance.push_back(pc.tolerance);
    }
    SocketCanTransport sim, fw;
    ASSERT_EQ(sim.open(config(can_interface())), CanStatus::Ok);
    ASSERT_EQ(fw.open(config(can_interface(), jacobid::Span<const CanFilter>(filters.data(), filters.size()))), CanStatus::Ok);
    JointDecoderSet<4> set;
    ASSERT_EQ(set.configure(joints).status, ConfigStatus::Ok);
    std::array<CanFrame, 32> rx{};
    for (int k = 0; k < 300; ++k) {
        const double q = 15.0 * std::sin(7e-3 * k);
        const double tau = std::cos(11e-3 * k);
        std::size_t expected = 0;
        for (std::size_t i = 0; i < joints.size(); ++i) {
            for (const CanFrame& f : encode(joints[i], (i % 2 ? -q : q), tau)) {
                ASSERT_EQ(sim.send(f), CanStatus::Ok);
                ++expected;
            }
        }
        set.begin_cycle();
        std::size_t n = 0;
        for (const CanFrame& f : receive_frames(fw, expected)) rx[n++] = f;
        ASSERT_EQ(n, expected) << "cycle " << k;
        ASSERT_EQ(set.dispatch(jacobid::Span<const CanFrame>(rx.data(), n)), n);
        for (std::size_t i = 0; i < joints.size(); ++i) {
            ASSERT_TRUE(set.state(i).fresh()) << i;
            ASSERT_NEAR(set.state(i).position, (i % 2 ? -q : q), tolerance[i].position) << i << " cycle " << k;
            ASSERT_NEAR(set.state(i).torque, tau, tolerance[i].torque + 1e-9) << i << " cycle " << k;
        }
    }
}

}  // namespace
