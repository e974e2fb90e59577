// SPDX-License-Identifier: MIT
// Command frames of every profile (controller -> drive), byte for byte. Each expected frame is written
// out from the protocol's layout (docs/profiles.md, "Command frames"), never taken from the encoder.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "hal_test_util.hpp"
#include "jacobid/hal/profile_registry.hpp"

namespace {

using namespace jacobid::hal;
using jacobid::hal::test::frame;
using jacobid::hal::test::hex;

JointCommand position_command(double q, double qd, double tau, double kp = 0.0, double kd = 0.0) {
    JointCommand c;
    c.mode = CommandMode::Position;
    c.position = q;
    c.velocity = qd;
    c.torque = tau;
    c.kp = kp;
    c.kd = kd;
    return c;
}
JointCommand torque_command(double tau) {
    JointCommand c;
    c.mode = CommandMode::Torque;
    c.torque = tau;
    return c;
}

void expect_frame(const CanFrame& actual, const CanFrame& expected) {
    EXPECT_EQ(actual.id, expected.id);
    EXPECT_EQ(actual.flags, expected.flags);
    EXPECT_EQ(static_cast<int>(actual.len), static_cast<int>(expected.len));
    EXPECT_EQ(hex(actual), hex(expected));
}

// --- MIT mode ---

mit::JointConfig mit_motor(std::uint8_t id) {
    mit::JointConfig c;
    c.motor_id = id;  // AK80-9 ranges: +-12.5 rad, +-50 rad/s, +-18 N.m, kp 0..500, kd 0..5
    return c;
}

TEST(HalMitCommand, PacksEveryFieldAtItsBits) {
    // Ranges where a value is its own code, so each field's bits are visible: position 0x1234,
    // velocity 0xABC, kp 0x123, kd 0x456, torque 0x789.
    //   d0 d1 = position 12 34; d2 = velocity bits 11..4 AB; d3 = velocity bits 3..0 | kp bits 11..8 = C1;
    //   d4 = kp bits 7..0 23; d5 = kd bits 11..4 45; d6 = kd bits 3..0 | torque bits 11..8 = 67; d7 = 89.
    mit::JointConfig c = mit_motor(3);
    c.ranges.p_min = 0.0, c.ranges.p_max = 65535.0;
    c.ranges.v_min = 0.0, c.ranges.v_max = 4095.0;
    c.ranges.t_min = 0.0, c.ranges.t_max = 4095.0;
    c.ranges.kp_max = 4095.0, c.ranges.kd_max = 4095.0;
    CanFrame f;
    mit::encode_command(c, position_command(0x1234, 0xABC, 0x789, 0x123, 0x456), &f);
    expect_frame(f, frame(0x003, {0x12, 0x34, 0xAB, 0xC1, 0x23, 0x45, 0x67, 0x89}));
}

TEST(HalMitCommand, ScalesOverTheConfiguredRanges) {
    CanFrame f;
    // p_max -> 0xFFFF; v = 0 -> (0 + 50) * 4095 / 100 = 2047.5 -> 0x800; kp 500 -> 0xFFF; kd 0 -> 0;
    // t = -18 -> 0.  Bytes: FF FF | 80 | 0F | FF | 00 | 00 | 00.
    mit::encode_command(mit_motor(1), position_command(12.5, 0.0, -18.0, 500.0, 0.0), &f);
    expect_frame(f, frame(0x001, {0xFF, 0xFF, 0x80, 0x0F, 0xFF, 0x00, 0x00, 0x00}));
    // p_min -> 0; v_max -> 0xFFF; kp 0; kd 5 -> 0xFFF; t_max -> 0xFFF.  Bytes: 00 00 | FF | F0 | 00 | FF | FF | FF.
    mit::encode_command(mit_motor(1), position_command(-12.5, 50.0, 18.0, 0.0, 5.0), &f);
    expect_frame(f, frame(0x001, {0x00, 0x00, 0xFF, 0xF0, 0x00, 0xFF, 0xFF, 0xFF}));
}

TEST(HalMitCommand, MapsTheLinkSideAndSaturates) {
    mit::JointConfig c = mit_motor(2);
    c.mapping.gear_ratio = 2.0;
    c.mapping.direction = -1.0;
    CanFrame f;
    // Link 6.25 rad -> motor -12.5 rad (p_min, 0x0000); link 100 rad/s -> motor -200 rad/s, clamped to
    // v_min (0x000); link -36 N.m -> motor +18 N.m (t_max, 0xFFF); kp 1000 clamps to 0xFFF, kd -1 to 0.
    mit::encode_command(c, position_command(6.25, 100.0, -36.0, 1000.0, -1.0), &f);
    expect_frame(f, frame(0x002, {0x00, 0x00, 0x00, 0x0F, 0xFF, 0x00, 0x0F, 0xFF}));
}

TEST(HalMitCommand, TorqueModeSendsZeroGains) {
    CanFrame f;
    // Mid position 0 rad -> 32767.5 -> 0x8000, v 0 -> 0x800, kp = kd = 0, t 9 N.m -> 27 * 4095 / 36 =
    // 3071.25 -> 0xBFF.  Bytes: 80 00 | 80 | 00 | 00 | 00 | 0B | FF.
    mit::encode_command(mit_motor(1), torque_command(9.0), &f);
    expect_frame(f, frame(0x001, {0x80, 0x00, 0x80, 0x00, 0x00, 0x00, 0x0B, 0xFF}));
}

TEST(HalMitCommand, ModeRequests) {
    CanFrame f;
    mit::encode_mode_request(mit_motor(4), mit::ModeRequest::EnterMotorMode, f);
    expect_frame(f, frame(0x004, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFC}));
    mit::encode_mode_request(mit_motor(4), mit::ModeRequest::ExitMotorMode, f);
    expect_frame(f, frame(0x004, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFD}));
    mit::encode_mode_request(mit_motor(4), mit::ModeRequest::SetZeroPosition, f);
    expect_frame(f, frame(0x004, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFE}));
}

TEST(HalMitCommand, DriveSideReadsTheFieldsBack) {
    mit::RawCommand r;
    ASSERT_EQ(mit::unpack_command(frame(0x003, {0x12, 0x34, 0xAB, 0xC1, 0x23, 0x45, 0x67, 0x89}), r), DecodeStatus::Ok);
    EXPECT_EQ(r.position, 0x1234);
    EXPECT_EQ(r.velocity, 0xABC);
    EXPECT_EQ(r.kp, 0x123);
    EXPECT_EQ(r.kd, 0x456);
    EXPECT_EQ(r.torque, 0x789);
    EXPECT_EQ(mit::unpack_command(frame(0x003, {0x12, 0x34}), r), DecodeStatus::Short);
}

// --- ODrive CANSimple ---

odrive::JointConfig axis(std::uint8_t node, double gear) {
    odrive::JointConfig c;
    c.node_id = node;
    c.mapping.gear_ratio = gear;
    c.mapping.torque_constant = 0.05;
    return c;
}

TEST(HalOdriveCommand, SetInputPosWithFeedForwards) {
    CanFrame f;
    // Node 3, cmd 0x00C -> id 3 << 5 | 0x0C = 0x06C. Input_Pos 1.5 turns = float 0x3FC00000 -> 00 00 C0 3F;
    // Vel_FF -2 turn/s -> -2000 = 0xF830 -> 30 F8; Torque_FF 0.5 N.m -> 500 = 0x01F4 -> F4 01.
    odrive::encode_command(axis(3, 1.0), position_command(1.5 * kTwoPi, -2.0 * kTwoPi, 0.5), &f);
    expect_frame(f, frame(0x06C, {0x00, 0x00, 0xC0, 0x3F, 0x30, 0xF8, 0xF4, 0x01}));
    // Gear 10: link 0.15 turn -> motor 1.5 turns; link 5 N.m -> motor 0.5 N.m; feed-forwards saturate at
    // int16: 40 turn/s -> 32767 = 7F FF -> FF 7F.
    odrive::encode_command(axis(3, 10.0), position_command(0.15 * kTwoPi, 4.0 * kTwoPi, 5.0), &f);
    expect_frame(f, frame(0x06C, {0x00, 0x00, 0xC0, 0x3F, 0xFF, 0x7F, 0xF4, 0x01}));
}

TEST(HalOdriveCommand, SetInputTorqueAndAxisState) {
    CanFrame f;
    // Node 3, cmd 0x00E -> 0x06E. Input_Torque: link 15 N.m / gear 10 = 1.5 N.m = 0x3FC00000.
    odrive::encode_command(axis(3, 10.0), torque_command(15.0), &f);
    expect_frame(f, frame(0x06E, {0x00, 0x00, 0xC0, 0x3F}));
    // -2.0 N.m = 0xC0000000.
    odrive::encode_command(axis(3, 1.0), torque_command(-2.0), &f);
    expect_frame(f, frame(0x06E, {0x00, 0x00, 0x00, 0xC0}));
    // Set_Axis_State (0x007), node 3 -> 0x067: CLOSED_LOOP_CONTROL (8) as uint32 LE, then IDLE (1).
    odrive::pack_axis_state(3, odrive::kAxisStateClosedLoopControl, f);
    expect_frame(f, frame(0x067, {0x08, 0x00, 0x00, 0x00}));
    odrive::pack_axis_state(3, odrive::kAxisStateIdle, f);
    expect_frame(f, frame(0x067, {0x01, 0x00, 0x00, 0x00}));
}

TEST(HalOdriveCommand, CircularSetpointsAreSentWrapped) {
    odrive::JointConfig c = axis(1, 1.0);
    c.position_wrap_turns = 1.0;
    CanFrame f;
    // 2.25 turns -> 0.25 turn = 0x3E800000 -> 00 00 80 3E; node 1 -> id 0x02C.
    odrive::encode_command(c, position_command(2.25 * kTwoPi, 0.0, 0.0), &f);
    expect_frame(f, frame(0x02C, {0x00, 0x00, 0x80, 0x3E, 0x00, 0x00, 0x00, 0x00}));
}

TEST(HalOdriveCommand, DriveSideReadsSetInputPos) {
    odrive::InputPos r;
    ASSERT_EQ(odrive::unpack_input_pos(frame(0x06C, {0x00, 0x00, 0xC0, 0x3F, 0x30, 0xF8, 0xF4, 0x01}), r), DecodeStatus::Ok);
    EXPECT_EQ(r.position_turns, 1.5f);
    EXPECT_EQ(r.velocity_ff, -2000);
    EXPECT_EQ(r.torque_ff, 500);
}

// --- CiA 402 ---

cia402::JointConfig drive(std::uint8_t node) {
    cia402::JointConfig c;
    c.node_id = node;
    c.counts_per_revolution = 4096.0;
    c.layout.effort = cia402::EffortObject::TorqueActual;
    c.rated_torque = 2.0;
    return c;
}

TEST(HalCia402Command, TargetPositionThroughRpdo1) {
    CanFrame f;
    // RPDO1 of node 5: 0x200 + 5 = 0x205. Controlword 0x000F -> 0F 00; one turn = 4096 counts = 0x00001000
    // -> 00 10 00 00.
    cia402::encode_command(drive(5), cia402::kEnableOperation, position_command(kTwoPi, 0.0, 0.0), f);
    expect_frame(f, frame(0x205, {0x0F, 0x00, 0x00, 0x10, 0x00, 0x00}));
    // -1 turn = -4096 = 0xFFFFF000 -> 00 F0 FF FF; controlword shutdown 0x0006.
    cia402::encode_command(drive(5), cia402::kShutdown, position_command(-kTwoPi, 0.0, 0.0), f);
    expect_frame(f, frame(0x205, {0x06, 0x00, 0x00, 0xF0, 0xFF, 0xFF}));
}

TEST(HalCia402Command, TargetTorqueInPerMilleOfRatedTorque) {
    CanFrame f;
    // 1 N.m of a 2 N.m rated torque = 500 per mille = 0x01F4 -> F4 01.
    cia402::encode_command(drive(5), cia402::kEnableOperation, torque_command(1.0), f);
    expect_frame(f, frame(0x205, {0x0F, 0x00, 0xF4, 0x01}));
    // Gear 50: link -50 N.m -> motor -1 N.m... = -500 = 0xFE0C -> 0C FE.
    cia402::JointConfig c = drive(5);
    c.mapping.gear_ratio = 50.0;
    cia402::encode_command(c, cia402::kEnableOperation, torque_command(-50.0), f);
    expect_frame(f, frame(0x205, {0x0F, 0x00, 0x0C, 0xFE}));
}

TEST(HalCia402Command, CustomRpdoLayout) {
    cia402::JointConfig c = drive(5);
    c.command.cob_id = 0x305;  // RPDO2
    c.command.controlword_byte = 4;
    c.command.target_byte = 0;
    ASSERT_EQ(cia402::validate(c), ConfigStatus::Ok);
    CanFrame f;
    // Target position bytes 0..3 (0x1000 -> 00 10 00 00), controlword bytes 4..5 (0F 00).
    cia402::encode_command(c, cia402::kEnableOperation, position_command(kTwoPi, 0.0, 0.0), f);
    expect_frame(f, frame(0x305, {0x00, 0x10, 0x00, 0x00, 0x0F, 0x00}));
    c.command.target_byte = 3;  // overlaps the controlword
    EXPECT_EQ(cia402::validate(c), ConfigStatus::InvalidLayout);
}

TEST(HalCia402Command, TorqueNeedsTheRatedTorque) {
    cia402::JointConfig c = drive(5);
    c.layout.effort = cia402::EffortObject::CurrentActual;
    c.rated_current = 3.0;
    c.mapping.torque_constant = 0.2;
    c.rated_torque = 0.0;
    EXPECT_EQ(cia402::validate_command(c, CommandMode::Torque), ConfigStatus::InvalidScale);
    EXPECT_EQ(cia402::validate_command(c, CommandMode::Position), ConfigStatus::Ok);
    CanFrame f;
    cia402::encode_command(c, cia402::kEnableOperation, torque_command(1.0), f);
    expect_frame(f, frame(0x205, {0x0F, 0x00, 0x00, 0x00}));  // zero torque, never a guess
}

TEST(HalCia402Command, EnablerWalksTheStateMachine) {
    cia402::DriveEnabler e;
    // Statuswords (bits 0..6): switch on disabled x1xx 0000, ready to switch on x01x 0001, switched on
    // x01x 0011, operation enabled x01x 0111, fault x0xx 1000. Bit 4 (voltage enabled) and bit 9 (remote)
    // are set as drives do.
    EXPECT_EQ(e.next(0x0250, true), 0x06);  // switch on disabled -> shutdown
    EXPECT_EQ(e.next(0x0231, true), 0x07);  // ready to switch on -> switch on
    EXPECT_EQ(e.next(0x0233, true), 0x0F);  // switched on -> enable operation
    EXPECT_EQ(e.next(0x0237, true), 0x0F);  // operation enabled: stay
    EXPECT_EQ(e.next(0x0237, false), 0x06);  // disable: shutdown
    EXPECT_EQ(e.next(0x0218, true), 0x80);  // fault -> fault reset (rising edge of bit 7)
    EXPECT_EQ(e.next(0x0218, true), 0x00);  // still in fault: bit 7 low again, so the next reset is an edge
    EXPECT_EQ(e.next(0x0218, true), 0x80);
    EXPECT_EQ(e.next(0x0000, true), 0x00);  // not ready to switch on: wait
    EXPECT_EQ(e.next(0x0217, true), 0x00);  // quick stop active -> disable voltage (then switch on disabled)
    EXPECT_EQ(cia402::drive_state(0x021F), cia402::DriveState::FaultReactionActive);
    EXPECT_EQ(cia402::drive_state(0x0237), cia402::DriveState::OperationEnabled);
}

TEST(HalCia402Command, DriveSideReadsTheRpdo) {
    cia402::RawRpdo r;
    ASSERT_EQ(cia402::unpack_rpdo({}, CommandMode::Position, frame(0x205, {0x0F, 0x00, 0x00, 0xF0, 0xFF, 0xFF}), r), DecodeStatus::Ok);
    EXPECT_EQ(r.controlword, 0x0F);
    EXPECT_EQ(r.target_position, -4096);
    ASSERT_EQ(cia402::unpack_rpdo({}, CommandMode::Torque, frame(0x205, {0x0F, 0x00, 0x0C, 0xFE}), r), DecodeStatus::Ok);
    EXPECT_EQ(r.target_torque_per_mille, -500);
    EXPECT_EQ(cia402::unpack_rpdo({}, CommandMode::Position, frame(0x205, {0x0F, 0x00, 0x0C, 0xFE}), r), DecodeStatus::Short);
}

// --- generic ---

generic::JointConfig generic_joint() {
    generic::JointConfig c;
    c.position.can_id = 0x280;
    c.effort.can_id = 0x280;
    c.effort.byte_offset = 2;
    generic::CommandLayout& k = c.command;
    k.has_position = true;  // 0x300 bytes 0..3, INT32 LE, 0.001 rad
    k.position.can_id = 0x300;
    k.position.bit_width = 32;
    k.position.scale = 0.001;
    k.has_torque = true;    // 0x300 bytes 4..5, INT16 LE, 0.01 N.m
    k.torque.can_id = 0x300;
    k.torque.byte_offset = 4;
    k.torque.scale = 0.01;
    k.has_velocity = true;  // 0x301 bytes 0..1, INT16 big-endian, 0.01 rad/s
    k.velocity.can_id = 0x301;
    k.velocity.order = ByteOrder::BigEndian;
    k.velocity.scale = 0.01;
    return c;
}

TEST(HalGenericCommand, WritesTheUsersSignals) {
    const generic::JointConfig c = generic_joint();
    ASSERT_EQ(generic::validate(c), ConfigStatus::Ok);
    std::array<CanFrame, kMaxCommandFrames> out{};
    // Position 1 rad = 1000 = 0x000003E8 -> E8 03 00 00; torque -2.5 N.m = -250 = 0xFF06 -> 06 FF;
    // velocity 3 rad/s = 300 = 0x012C big-endian -> 01 2C.
    ASSERT_EQ(generic::encode_command(c, position_command(1.0, 3.0, -2.5), out.data()), 2u);
    expect_frame(out[0], frame(0x300, {0xE8, 0x03, 0x00, 0x00, 0x06, 0xFF}));
    expect_frame(out[1], frame(0x301, {0x01, 0x2C}));
    // Torque mode: the torque field alone (its frame still spans bytes 0..5).
    ASSERT_EQ(generic::encode_command(c, torque_command(-2.5), out.data()), 1u);
    expect_frame(out[0], frame(0x300, {0x00, 0x00, 0x00, 0x00, 0x06, 0xFF}));
}

// --- the registry ---

TEST(HalProfileRegistry, CommandsGoThroughTheProfilesOwnEncoder) {
    std::array<CanFrame, kMaxCommandFrames> out{};
    const ProfileConfig odrive_axis = axis(3, 1.0);
    ASSERT_EQ(encode_command(odrive_axis, torque_command(-2.0), out.data()), 1u);
    expect_frame(out[0], frame(0x06E, {0x00, 0x00, 0x00, 0xC0}));
    // CiA 402 through the registry: operation enabled (0x0F), the enabling itself is DriveEnabler's.
    const ProfileConfig cia = drive(5);
    ASSERT_EQ(encode_command(cia, torque_command(1.0), out.data()), 1u);
    expect_frame(out[0], frame(0x205, {0x0F, 0x00, 0xF4, 0x01}));
    const ProfileConfig g = generic_joint();
    EXPECT_EQ(encode_command(g, position_command(1.0, 3.0, -2.5), out.data()), 2u);
}

TEST(HalProfileRegistry, NamesAndTelemetryFrameCounts) {
    EXPECT_STREQ(profile_name(ProfileConfig{mit_motor(1)}), "mit");
    EXPECT_STREQ(profile_name(ProfileConfig{drive(1)}), "cia402");
    EXPECT_STREQ(profile_name(ProfileConfig{axis(1, 1.0)}), "odrive");
    EXPECT_STREQ(profile_name(ProfileConfig{generic_joint()}), "generic");
    EXPECT_EQ(kMaxTelemetryFrames, 3u);
    int found = 0;
    EXPECT_TRUE(with_profile_named("odrive", [&](auto tag) { found = static_cast<int>(decltype(tag)::type::kTelemetryFrames); }));
    EXPECT_EQ(found, 2);
    EXPECT_FALSE(with_profile_named("canopen", [](auto) {}));
}

// The drive side (what a simulated drive following commands reads) decodes the controller side's frames
// back to the link-side command, within each field's quantization.
TEST(HalProfileRegistry, DriveSideDecodesTheCommandFrames) {
    mit::JointConfig m = mit_motor(2);
    m.mapping.gear_ratio = 4.0;
    cia402::JointConfig d = drive(5);
    d.mapping.gear_ratio = 10.0;
    const std::array<ProfileConfig, 4> joints = {m, axis(3, 10.0), d, generic_joint()};
    for (const ProfileConfig& joint : joints) {
        for (const JointCommand& sent : {position_command(0.7, -0.4, 1.5, 120.0, 2.5), torque_command(-1.25)}) {
            std::array<CanFrame, kMaxCommandFrames> out{};
            const std::size_t n = encode_command(joint, sent, out.data());
            ASSERT_GE(n, 1u) << profile_name(joint);
            JointCommand got;
            for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(decode_command(joint, sent.mode, out[i], got), DecodeStatus::Ok) << profile_name(joint);
            SCOPED_TRACE(profile_name(joint));
            EXPECT_EQ(got.mode, sent.mode);
            // CiA 402's position RPDO carries no torque feed-forward (docs/profiles.md).
            const bool has_torque = sent.mode == CommandMode::Torque || std::string(profile_name(joint)) != "cia402";
            if (has_torque) {
                EXPECT_NEAR(got.torque, sent.torque, 0.05);
            }
            if (sent.mode == CommandMode::Position) {
                EXPECT_NEAR(got.position, sent.position, 1e-3);
            }
        }
    }
    // MIT gains and velocity, from the hand-written frame of PacksEveryFieldAtItsBits' scaling test:
    // kp 0xFFF = 500, kd 0 -> still Position mode; a mode request is not a setpoint.
    JointCommand got;
    ASSERT_EQ(mit::decode_command(mit_motor(1), CommandMode::Position, frame(0x001, {0xFF, 0xFF, 0x80, 0x0F, 0xFF, 0x00, 0x00, 0x00}), got),
              DecodeStatus::Ok);
    EXPECT_EQ(got.mode, CommandMode::Position);
    EXPECT_DOUBLE_EQ(got.position, 12.5);
    EXPECT_DOUBLE_EQ(got.kp, 500.0);
    EXPECT_DOUBLE_EQ(got.torque, -18.0);
    EXPECT_EQ(mit::decode_command(mit_motor(1), CommandMode::Position, frame(0x001, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFC}), got),
              DecodeStatus::NotMine);
    // Another node's or another message's frames are not the joint's.
    EXPECT_EQ(odrive::decode_command(axis(3, 1.0), CommandMode::Position, frame(0x08C, {0, 0, 0, 0, 0, 0, 0, 0}), got), DecodeStatus::NotMine);
    EXPECT_EQ(odrive::decode_command(axis(3, 1.0), CommandMode::Position, frame(0x069, {0, 0, 0, 0, 0, 0, 0, 0}), got), DecodeStatus::NotMine);
    EXPECT_EQ(cia402::decode_command(drive(5), CommandMode::Position, frame(0x206, {0x0F, 0x00, 0, 0, 0, 0}), got), DecodeStatus::NotMine);
}

}  // namespace
