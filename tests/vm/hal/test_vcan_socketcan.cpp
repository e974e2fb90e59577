// SPDX-License-Identifier: MIT
// SocketCanTransport against the kernel's CAN stack on a vcan interface (label vcan): round trip with
// kernel timestamps, kernel acceptance filters, error frames, receive overflow, CAN FD.
// Runs where vcan exists: on a host through tests/vm/run-on-host.sh, or in the VM (scripts/vm-test.sh).
#include <gtest/gtest.h>

#include <linux/can/error.h>

#include <array>
#include <chrono>
#include <thread>
#include <vector>

#include "vcan_test_util.hpp"
#include "../../unit/hal/hal_test_util.hpp"

namespace {

using namespace jacobid::hal;
using namespace jacobid::hal::vcan_test;
using jacobid::hal::test::frame;

class VcanSocketCan : public ::testing::Test {
protected:
    void SetUp() override { ASSERT_TRUE(interface_exists(can_interface())); }
};

TEST_F(VcanSocketCan, OpensTheInterfaceAndRefusesUnknownOnes) {
    SocketCanTransport t;
    ASSERT_EQ(t.open(config(can_interface())), CanStatus::Ok) << describe(t.open(config(can_interface())));
    EXPECT_TRUE(t.is_open());
    EXPECT_EQ(t.open(config(can_interface())), CanStatus::AlreadyOpen);
    SocketCanTransport none;
    EXPECT_EQ(none.open(config("jacobidnone0")), CanStatus::NoSuchInterface);
    EXPECT_FALSE(none.is_open());
    SocketCanConfig fd = config(can_interface());
    fd.fd_frames = true;  // vcan0 is classic CAN (MTU 16)
    SocketCanTransport f;
    EXPECT_EQ(f.open(fd), CanStatus::FdNotSupported);
    t.close();
    EXPECT_FALSE(t.is_open());
    CanFrame x;
    EXPECT_EQ(t.receive(x), CanStatus::NotOpen);
}

TEST_F(VcanSocketCan, RoundTripCarriesEveryFieldAndAKernelTimestamp) {
    SocketCanTransport tx, rx;
    ASSERT_EQ(tx.open(config(can_interface())), CanStatus::Ok);
    ASSERT_EQ(rx.open(config(can_interface())), CanStatus::Ok);
    const std::vector<CanFrame> sent = {
        frame(0x123, {0x11, 0x22, 0x33}), frame(0x7FF, {1, 2, 3, 4, 5, 6, 7, 8}),
        frame(0x1ABCDEF0, {0xA5}, kCanExtended), frame(0x000, {}), frame(0x555, {}, kCanRemote)};
    const std::int64_t before = realtime_ns();
    for (const CanFrame& f : sent) ASSERT_EQ(tx.send(f), CanStatus::Ok);
    const std::vector<CanFrame> got = receive_frames(rx, sent.size());
    const std::int64_t after = realtime_ns();
    ASSERT_EQ(got.size(), sent.size());
    std::int64_t previous = 0;
    for (std::size_t i = 0; i < sent.size(); ++i) {
        EXPECT_EQ(got[i].id, sent[i].id) << i;
        EXPECT_EQ(got[i].flags, sent[i].flags) << i;
        EXPECT_EQ(got[i].len, sent[i].len) << i;
        EXPECT_EQ(got[i].data, sent[i].data) << i;
        // SO_TIMESTAMPNS: CLOCK_REALTIME when the kernel received the frame, in order, within the test.
        EXPECT_GE(got[i].timestamp_ns, before) << i;
        EXPECT_LE(got[i].timestamp_ns, after) << i;
        EXPECT_GE(got[i].timestamp_ns, previous) << i;
        previous = got[i].timestamp_ns;
    }
    EXPECT_EQ(tx.counters().tx_frames, sent.size());
    EXPECT_EQ(rx.counters().rx_frames, sent.size());
    EXPECT_EQ(rx.counters().rx_overflows, 0u);
    // Without receive_own the sender does not see its own frames...
    CanFrame f;
    EXPECT_EQ(tx.receive(f), CanStatus::Empty);
    // ...with it, it does.
    SocketCanConfig own = config(can_interface());
    own.receive_own = true;
    SocketCanTransport echo;
    ASSERT_EQ(echo.open(own), CanStatus::Ok);
    ASSERT_EQ(echo.send(frame(0x321, {9})), CanStatus::Ok);
    const auto back = receive_frames(echo, 1);
    ASSERT_EQ(back.size(), 1u);
    EXPECT_EQ(back[0].id, 0x321u);
}

TEST_F(VcanSocketCan, TimestampsFollowTheSendTimeNotTheReadTime) {
    SocketCanTransport tx, rx;
    ASSERT_EQ(tx.open(config(can_interface())), CanStatus::Ok);
    ASSERT_EQ(rx.open(config(can_interface())), CanStatus::Ok);
    ASSERT_EQ(tx.send(frame(0x100, {1})), CanStatus::Ok);
    const std::int64_t sent_at = realtime_ns();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_EQ(tx.send(frame(0x101, {2})), CanStatus::Ok);
    const auto got = receive_frames(rx, 2);
    ASSERT_EQ(got.size(), 2u);
    // Read together, stamped apart: the first stamp is near its send, not near the read 50 ms later.
    EXPECT_LT(got[0].timestamp_ns, sent_at + 20000000LL);
    EXPECT_GE(got[1].timestamp_ns - got[0].timestamp_ns, 45000000LL);
}

TEST_F(VcanSocketCan, KernelFiltersDeliverExactlyWhatMatchesAccepts) {
    const std::array<CanFilter, 4> filters = {
        exact_filter(0x181), exact_filter(0x18FF0001, true), CanFilter{0x200, 0x700, CanIdFormat::Standard, false},
        CanFilter{0x7E8, 0x7FF, CanIdFormat::Any, true}};
    SocketCanTransport tx, filtered, all;
    ASSERT_EQ(tx.open(config(can_interface())), CanStatus::Ok);
    ASSERT_EQ(filtered.open(config(can_interface(), filters)), CanStatus::Ok);
    ASSERT_EQ(all.open(config(can_interface())), CanStatus::Ok);
    std::vector<CanFrame> sent;
    for (std::uint32_t id : {0x181u, 0x182u, 0x200u, 0x2FFu, 0x300u, 0x7E8u, 0x000u}) {
        sent.push_back(frame(id, {static_cast<std::uint8_t>(id)}));
        sent.push_back(frame(id, {}, kCanRemote));
        sent.push_back(frame(id, {1, 2}, kCanExtended));
    }
    sent.push_back(frame(0x18FF0001, {7}, kCanExtended));
    sent.push_back(frame(0x18FF0002, {7}, kCanExtended));
    std::vector<CanFrame> expected;
    for (const CanFrame& f : sent) {
        if (matches_any(filters, filters.size(), f)) expected.push_back(f);
        ASSERT_EQ(tx.send(f), CanStatus::Ok);
    }
    ASSERT_GT(expected.size(), 3u);
    ASSERT_LT(expected.size(), sent.size());
    const auto everything = receive_frames(all, sent.size());
    EXPECT_EQ(everything.size(), sent.size());
    const auto got = receive_frames(filtered, sent.size(), 300);  // waits out any frame wrongly let through
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_EQ(got[i].id, expected[i].id) << i;
        EXPECT_EQ(got[i].flags, expected[i].flags) << i;
    }
}

TEST_F(VcanSocketCan, ErrorFramesAreCountedWithTheirClassAndNeverHandedOn) {
    RawSocket injector(can_interface());
    ASSERT_TRUE(injector.ok()) << std::strerror(errno);
    SocketCanTransport counting, ignoring;
    ASSERT_EQ(counting.open(config(can_interface())), CanStatus::Ok);  // error_frames = true by default
    SocketCanConfig no_errors = config(can_interface());
    no_errors.error_frames = false;
    ASSERT_EQ(ignoring.open(no_errors), CanStatus::Ok);

    can_frame err{};
    err.can_id = CAN_ERR_FLAG | CAN_ERR_CRTL;
    err.len = CAN_ERR_DLC;
    err.data[1] = CAN_ERR_CRTL_RX_WARNING;
    ASSERT_TRUE(injector.send(err));
    err = can_frame{};
    err.can_id = CAN_ERR_FLAG | CAN_ERR_BUSOFF;
    err.len = CAN_ERR_DLC;
    ASSERT_TRUE(injector.send(err));
    can_frame data{};
    data.can_id = 0x42;
    data.len = 1;
    data.data[0] = 0x99;
    ASSERT_TRUE(injector.send(data));

    const auto got = receive_frames(counting, 1);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].id, 0x42u);
    EXPECT_FALSE(got[0].error());
    EXPECT_EQ(counting.counters().error_frames, 2u);
    EXPECT_EQ(counting.counters().last_error_class, static_cast<std::uint32_t>(CAN_ERR_BUSOFF));
    EXPECT_EQ(counting.counters().rx_frames, 1u);
    CanFrame f;
    EXPECT_EQ(counting.receive(f), CanStatus::Empty);

    const auto plain = receive_frames(ignoring, 1);
    ASSERT_EQ(plain.size(), 1u);
    EXPECT_EQ(plain[0].id, 0x42u);
    EXPECT_EQ(ignoring.counters().error_frames, 0u);  // the kernel did not deliver them at all

    // The transport refuses to put an error frame on the bus itself.
    SocketCanTransport tx;
    ASSERT_EQ(tx.open(config(can_interface())), CanStatus::Ok);
    EXPECT_EQ(tx.send(frame(CAN_ERR_CRTL, {0}, kCanError)), CanStatus::InvalidFrame);
}

TEST_F(VcanSocketCan, ReceiveOverflowIsCountedFromTheKernelDropCounter) {
    SocketCanTransport tx, rx;
    ASSERT_EQ(tx.open(config(can_interface())), CanStatus::Ok);
    SocketCanConfig small = config(can_interface());
    small.receive_buffer_bytes = 1;  // the kernel rounds up to its minimum: a few frames fit
    ASSERT_EQ(rx.open(small), CanStatus::Ok);
    constexpr int kBurst = 500;
    int sent = 0;
    for (int k = 0; k < kBurst; ++k) {
        CanStatus s = tx.send(frame(0x100 + static_cast<std::uint32_t>(k % 256), {static_cast<std::uint8_t>(k)}));
        for (int retry = 0; s == CanStatus::TxQueueFull && retry < 100; ++retry) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
            s = tx.send(frame(0x100 + static_cast<std::uint32_t>(k % 256), {static_cast<std::uint8_t>(k)}));
        }
        ASSERT_EQ(s, CanStatus::Ok) << k;
        ++sent;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::array<CanFrame, kBurst> buf{};
    const DrainResult first = rx.drain(buf);
    ASSERT_EQ(first.status, CanStatus::Ok);
    EXPECT_GT(first.count, 0u);
    EXPECT_LT(first.count, static_cast<std::size_t>(kBurst));
    // Drops reach us with the next frame the socket queues (SO_RXQ_OVFL rides on received frames): one
    // more frame after the drain carries the final count.
    ASSERT_EQ(tx.send(frame(0x7FF, {0xEE})), CanStatus::Ok);
    ++sent;
    const auto last = receive_frames(rx, 1);
    ASSERT_EQ(last.size(), 1u);
    EXPECT_EQ(last[0].id, 0x7FFu);
    EXPECT_GT(rx.counters().rx_overflows, 0u);
    EXPECT_EQ(rx.counters().rx_frames + rx.counters().rx_overflows, static_cast<std::uint64_t>(sent))
        << "received " << rx.counters().rx_frames << ", dropped " << rx.counters().rx_overflows;
}

TEST(VcanSocketCanFd, FdFramesRoundTripOnAnFdInterface) {
    ASSERT_TRUE(interface_exists(canfd_interface()));
    SocketCanConfig c = config(canfd_interface());
    c.fd_frames = true;
    SocketCanTransport tx, rx;
    ASSERT_EQ(tx.open(c), CanStatus::Ok);
    ASSERT_EQ(rx.open(c), CanStatus::Ok);
    CanFrame fd = frame(0x123, {}, kCanFd | kCanBitRateSwitch);
    fd.len = 48;
    for (std::size_t i = 0; i < fd.len; ++i) fd.data[i] = static_cast<std::uint8_t>(i * 3);
    ASSERT_EQ(tx.send(fd), CanStatus::Ok);
    ASSERT_EQ(tx.send(frame(0x124, {1, 2})), CanStatus::Ok);  // classic frames still pass on an FD socket
    const auto got = receive_frames(rx, 2);
    ASSERT_EQ(got.size(), 2u);
    EXPECT_TRUE(got[0].fd());
    EXPECT_EQ(got[0].len, 48);
    EXPECT_EQ(got[0].data, fd.data);
    EXPECT_EQ(got[0].flags, fd.flags);
    EXPECT_FALSE(got[1].fd());
    EXPECT_EQ(got[1].len, 2);
    // A classic socket on the FD interface never sees FD frames.
    SocketCanTransport classic;
    ASSERT_EQ(classic.open(config(canfd_interface())), CanStatus::Ok);
    ASSERT_EQ(tx.send(fd), CanStatus::Ok);
    ASSERT_EQ(tx.send(frame(0x125, {3})), CanStatus::Ok);
    const auto only_classic = receive_frames(classic, 2, 300);
    ASSERT_EQ(only_classic.size(), 1u);
    EXPECT_EQ(only_classic[0].id, 0x125u);
}

}  // namespace
