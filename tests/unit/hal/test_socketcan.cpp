// SPDX-License-Identifier: MIT
// SocketCAN backend without a CAN-capable kernel: open() errors, kernel structure conversion (frames
// and filters), control-message parsing, and the send/receive paths over a datagram socketpair standing
// in for the CAN socket (adopt()).
#include <gtest/gtest.h>

#include <linux/can/error.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <vector>

#include "hal_test_util.hpp"
#include "jacobid/hal/socketcan_transport.hpp"

namespace {

using namespace jacobid::hal;
using jacobid::hal::test::frame;

TEST(HalSocketCan, OpenReportsTheMissingKernelSupportOrTheMissingInterface) {
    // This machine's kernel has no CAN: socket(PF_CAN) fails with EAFNOSUPPORT. Under qemu with CAN the
    // same test meets a kernel with CAN and an interface that does not exist.
    const int probe = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
    const int probe_errno = errno;
    if (probe >= 0) ::close(probe);

    SocketCanTransport t;
    SocketCanConfig c;
    c.interface = "jacobidnone0";
    const CanStatus s = t.open(c);
    if (probe < 0 && probe_errno == EAFNOSUPPORT) {
        EXPECT_EQ(s, CanStatus::KernelHasNoCan) << describe(s);
        EXPECT_EQ(t.last_errno(), EAFNOSUPPORT);
        EXPECT_NE(std::strstr(describe(s), "EAFNOSUPPORT"), nullptr);
    } else {
        EXPECT_EQ(s, CanStatus::NoSuchInterface) << describe(s);
    }
    EXPECT_FALSE(t.is_open());
    EXPECT_EQ(t.native_handle(), -1);
    CanFrame f;
    EXPECT_EQ(t.receive(f), CanStatus::NotOpen);
    EXPECT_EQ(t.send(frame(0x1, {})), CanStatus::NotOpen);
}

TEST(HalSocketCan, OpenRejectsBadConfigurationBeforeAnySystemCall) {
    SocketCanTransport t;
    SocketCanConfig c;
    c.interface = "";
    EXPECT_EQ(t.open(c), CanStatus::InvalidInterfaceName);
    c.interface = "sixteen_chars_xx";  // IFNAMSIZ is 16 including the terminating zero
    EXPECT_EQ(t.open(c), CanStatus::InvalidInterfaceName);
    c.interface = nullptr;
    EXPECT_EQ(t.open(c), CanStatus::InvalidInterfaceName);
    std::array<CanFilter, SocketCanTransport::kMaxFilters + 1> filters{};
    c.interface = "can0";
    c.filters = filters;
    EXPECT_EQ(t.open(c), CanStatus::TooManyFilters);
    EXPECT_EQ(t.last_errno(), 0);
}

TEST(HalSocketCan, FrameToKernelSetsTheIdFlagsAndWireSize) {
    canfd_frame k{};
    std::size_t size = 0;
    ASSERT_EQ(to_kernel(frame(0x18FF0001, {0x11, 0x22}, kCanExtended), k, size), CanStatus::Ok);
    EXPECT_EQ(k.can_id, 0x98FF0001u);  // CAN_EFF_FLAG is bit 31
    EXPECT_EQ(k.len, 2);
    EXPECT_EQ(k.data[0], 0x11);
    EXPECT_EQ(k.data[1], 0x22);
    EXPECT_EQ(size, 16u);  // CAN_MTU: struct can_frame

    ASSERT_EQ(to_kernel(frame(0x123, {}, kCanRemote), k, size), CanStatus::Ok);
    EXPECT_EQ(k.can_id, 0x40000123u);  // CAN_RTR_FLAG is bit 30

    CanFrame fd = frame(0x7FF, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}, kCanFd | kCanBitRateSwitch);
    ASSERT_EQ(to_kernel(fd, k, size), CanStatus::Ok);
    EXPECT_EQ(size, 72u);      // CANFD_MTU
    EXPECT_EQ(k.flags, 0x05);  // CANFD_BRS 0x01 | CANFD_FDF 0x04
    EXPECT_EQ(k.data[11], 12);

    EXPECT_EQ(to_kernel(frame(0x800, {}), k, size), CanStatus::InvalidFrame);
    EXPECT_EQ(to_kernel(frame(0x1, {}, kCanError), k, size), CanStatus::InvalidFrame);
}

TEST(HalSocketCan, KernelToFrameRoundTripsAndRejectsBadSizes) {
    canfd_frame k{};
    k.can_id = 0x80000ABCu;  // extended 0xABC
    k.len = 3;
    k.data[0] = 0xA1;
    k.data[2] = 0xC3;
    k.data[5] = 0xFF;  // garbage beyond len must not leak into the frame
    CanFrame f;
    ASSERT_EQ(from_kernel(k, CAN_MTU, f), KernelFrameKind::Data);
    EXPECT_EQ(f.id, 0xABCu);
    EXPECT_TRUE(f.extended());
    EXPECT_FALSE(f.fd());
    EXPECT_EQ(f.len, 3);
    EXPECT_EQ(f.data[2], 0xC3);
    EXPECT_EQ(f.data[5], 0);

    k.len = 9;
    EXPECT_EQ(from_kernel(k, CAN_MTU, f), KernelFrameKind::Invalid);
    k.len = 48;
    k.flags = CANFD_ESI;
    ASSERT_EQ(from_kernel(k, CANFD_MTU, f), KernelFrameKind::Data);
    EXPECT_TRUE(f.fd());
    EXPECT_EQ(f.flags & kCanErrorStateIndicator, kCanErrorStateIndicator);
    k.len = 50;
    EXPECT_EQ(from_kernel(k, CANFD_MTU, f), KernelFrameKind::Invalid);
    EXPECT_EQ(from_kernel(k, 20, f), KernelFrameKind::Invalid);

    k = canfd_frame{};
    k.can_id = CAN_ERR_FLAG | CAN_ERR_BUSOFF;
    k.len = 8;
    ASSERT_EQ(from_kernel(k, CAN_MTU, f), KernelFrameKind::Error);
    EXPECT_EQ(f.id, static_cast<std::uint32_t>(CAN_ERR_BUSOFF));

    // Every valid frame survives CanFrame -> kernel -> CanFrame.
    for (const CanFrame& in : {frame(0x7FF, {9, 8, 7, 6, 5, 4, 3, 2}), frame(0x1ABCDEF0, {1}, kCanExtended),
                               frame(0x10, {}, kCanRemote)}) {
        std::size_t size = 0;
        ASSERT_EQ(to_kernel(in, k, size), CanStatus::Ok);
        CanFrame out;
        ASSERT_EQ(from_kernel(k, size, out), KernelFrameKind::Data);
        EXPECT_EQ(out.id, in.id);
        EXPECT_EQ(out.flags, in.flags);
        EXPECT_EQ(out.len, in.len);
        EXPECT_EQ(out.data, in.data);
    }
}

TEST(HalSocketCan, KernelFilterAcceptsExactlyWhatMatchesAccepts) {
    // The kernel rule (net/can/af_can.c): (can_id & mask) == (filter_id & mask), with the EFF and RTR
    // flags part of can_id. Checked against matches() over ids, formats and remote frames.
    const CanFilter filters[] = {
        {0x120, 0x7F0, CanIdFormat::Standard, false}, {0x120, 0x7F0, CanIdFormat::Extended, false},
        {0x120, 0x7F0, CanIdFormat::Any, false},      {0x185, 0x7FF, CanIdFormat::Standard, true},
        {0x0, 0x0, CanIdFormat::Any, true},           exact_filter(0x18FF0123, true),
    };
    std::vector<CanFrame> frames;
    for (std::uint32_t id = 0; id < 0x800; id += 3) {
        frames.push_back(frame(id, {}));
        frames.push_back(frame(id, {}, kCanRemote));
        frames.push_back(frame(id, {}, kCanExtended));
    }
    frames.push_back(frame(0x18FF0123, {}, kCanExtended));
    frames.push_back(frame(0x18FF0124, {}, kCanExtended));
    frames.push_back(frame(0x120 | (1u << 20), {}, kCanExtended));
    int accepted = 0;
    for (const CanFilter& flt : filters) {
        const can_filter kf = to_kernel_filter(flt);
        for (const CanFrame& f : frames) {
            canfd_frame k{};
            std::size_t size = 0;
            ASSERT_EQ(to_kernel(f, k, size), CanStatus::Ok);
            const bool kernel = (k.can_id & kf.can_mask) == (kf.can_id & kf.can_mask);
            EXPECT_EQ(kernel, matches(flt, f)) << std::hex << "filter id " << flt.id << " frame " << f.id;
            accepted += kernel ? 1 : 0;
        }
    }
    EXPECT_GT(accepted, 0);
}

TEST(HalSocketCan, ParsesTimestampAndDropCountFromControlMessages) {
    alignas(cmsghdr) unsigned char buf[CMSG_SPACE(sizeof(timespec)) + CMSG_SPACE(sizeof(std::uint32_t))] = {};
    msghdr msg{};
    msg.msg_control = buf;
    msg.msg_controllen = sizeof buf;
    cmsghdr* c = CMSG_FIRSTHDR(&msg);
    c->cmsg_level = SOL_SOCKET;
    c->cmsg_type = SCM_TIMESTAMPNS;
    c->cmsg_len = CMSG_LEN(sizeof(timespec));
    const timespec ts{12, 345678901};
    std::memcpy(CMSG_DATA(c), &ts, sizeof ts);
    c = CMSG_NXTHDR(&msg, c);
    ASSERT_NE(c, nullptr);
    c->cmsg_level = SOL_SOCKET;
    c->cmsg_type = SO_RXQ_OVFL;
    c->cmsg_len = CMSG_LEN(sizeof(std::uint32_t));
    const std::uint32_t drops = 7;
    std::memcpy(CMSG_DATA(c), &drops, sizeof drops);

    const ReceiveControl rc = parse_receive_control(msg);
    EXPECT_TRUE(rc.has_timestamp);
    EXPECT_EQ(rc.timestamp_ns, 12345678901LL);
    EXPECT_TRUE(rc.has_drop_count);
    EXPECT_EQ(rc.drop_count, 7u);

    msghdr empty{};
    const ReceiveControl none = parse_receive_control(empty);
    EXPECT_FALSE(none.has_timestamp);
    EXPECT_FALSE(none.has_drop_count);
}

// A datagram socketpair carries struct can_frame bytes exactly like a CAN_RAW socket would.
class HalSocketCanAdopted : public ::testing::Test {
protected:
    void SetUp() override {
        int sv[2];
        ASSERT_EQ(::socketpair(AF_UNIX, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0, sv), 0);
        ASSERT_EQ(transport.adopt(sv[0], false), CanStatus::Ok);
        peer = sv[1];
    }
    void TearDown() override {
        if (peer >= 0) ::close(peer);
    }
    void peer_send(const canfd_frame& k, std::size_t size) { ASSERT_EQ(::send(peer, &k, size, 0), static_cast<ssize_t>(size)); }

    SocketCanTransport transport;
    int peer = -1;
};

TEST_F(HalSocketCanAdopted, ReceivesDataFramesAndConsumesErrorFrames) {
    canfd_frame k{};
    k.can_id = 0x181;
    k.len = 2;
    k.data[0] = 0x34;
    k.data[1] = 0x12;
    peer_send(k, CAN_MTU);
    canfd_frame err{};
    err.can_id = CAN_ERR_FLAG | CAN_ERR_CRTL;
    err.len = 8;
    peer_send(err, CAN_MTU);
    peer_send(k, 20);  // not a CAN_MTU datagram
    k.can_id = 0x182;
    peer_send(k, CAN_MTU);

    std::array<CanFrame, 8> out{};
    const DrainResult r = transport.drain(out);
    EXPECT_EQ(r.status, CanStatus::Ok);
    ASSERT_EQ(r.count, 2u);
    EXPECT_EQ(out[0].id, 0x181u);
    EXPECT_EQ(out[0].data[0], 0x34);
    EXPECT_EQ(out[0].timestamp_ns, 0);  // no SO_TIMESTAMPNS on this socket: "unknown"
    EXPECT_EQ(out[1].id, 0x182u);
    EXPECT_EQ(transport.counters().rx_frames, 2u);
    EXPECT_EQ(transport.counters().error_frames, 1u);
    EXPECT_EQ(transport.counters().last_error_class, static_cast<std::uint32_t>(CAN_ERR_CRTL));
    EXPECT_EQ(transport.counters().io_errors, 1u);
    CanFrame f;
    EXPECT_EQ(transport.receive(f), CanStatus::Empty);
}

TEST_F(HalSocketCanAdopted, SendsKernelFramesAndReportsAFullQueue) {
    ASSERT_EQ(transport.send(frame(0x7E0, {0x02, 0x01, 0x0C})), CanStatus::Ok);
    canfd_frame k{};
    ASSERT_EQ(::recv(peer, &k, sizeof k, 0), static_cast<ssize_t>(CAN_MTU));
    EXPECT_EQ(k.can_id, 0x7E0u);
    EXPECT_EQ(k.len, 3);
    EXPECT_EQ(k.data[2], 0x0C);

    EXPECT_EQ(transport.send(frame(0x1, {}, kCanFd)), CanStatus::FdNotEnabled);
    EXPECT_EQ(transport.send(frame(0x800, {})), CanStatus::InvalidFrame);

    // Nobody reads the peer: the queue fills and send() must return instead of blocking.
    CanStatus s = CanStatus::Ok;
    int sent = 0;
    while (s == CanStatus::Ok && sent < 100000) {
        s = transport.send(frame(0x10, {1, 2, 3, 4, 5, 6, 7, 8}));
        sent += s == CanStatus::Ok ? 1 : 0;
    }
    EXPECT_EQ(s, CanStatus::TxQueueFull) << describe(s);
    EXPECT_EQ(transport.counters().tx_queue_full, 1u);
    EXPECT_EQ(transport.counters().tx_frames, static_cast<std::uint64_t>(sent) + 1u);
}

TEST_F(HalSocketCanAdopted, ReportsIoErrorsWithErrno) {
    ::close(peer);
    peer = -1;
    EXPECT_EQ(transport.send(frame(0x1, {})), CanStatus::IoError);
    EXPECT_NE(transport.last_errno(), 0);
    EXPECT_EQ(transport.counters().io_errors, 1u);
    EXPECT_EQ(transport.adopt(3, false), CanStatus::AlreadyOpen);
    transport.close();
    EXPECT_FALSE(transport.is_open());
}

}  // namespace
