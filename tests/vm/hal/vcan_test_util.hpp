// SPDX-License-Identifier: MIT
#pragma once
// Helpers of the vcan tests: the interface under test, waiting for frames, raw CAN sockets for what the
// transport must not do itself (inject error frames).
#include <gtest/gtest.h>

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "jacobid/hal/socketcan_transport.hpp"

namespace jacobid::hal::vcan_test {

// The classic-CAN interface (JACOBID_VCAN, default vcan0) and the CAN FD one (JACOBID_VCANFD, default
// vcan1, MTU 72): made by tests/vm/run-on-host.sh, or by jacobid-vcan-link in the VM.
inline const char* can_interface() {
    const char* e = std::getenv("JACOBID_VCAN");
    return e && *e ? e : "vcan0";
}
inline const char* canfd_interface() {
    const char* e = std::getenv("JACOBID_VCANFD");
    return e && *e ? e : "vcan1";
}

inline std::int64_t realtime_ns() {
    timespec ts{};
    clock_gettime(CLOCK_REALTIME, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

inline SocketCanConfig config(const char* iface, Span<const CanFilter> filters = {}) {
    SocketCanConfig c;
    c.interface = iface;
    c.filters = filters;
    return c;
}

// Receives until `want` data frames arrived or `timeout_ms` passed without any; returns what arrived.
inline std::vector<CanFrame> receive_frames(SocketCanTransport& t, std::size_t want, int timeout_ms = 1000) {
    std::vector<CanFrame> out;
    while (out.size() < want) {
        CanFrame f;
        const CanStatus s = t.receive(f);
        if (s == CanStatus::Ok) {
            out.push_back(f);
            continue;
        }
        if (s != CanStatus::Empty) {
            ADD_FAILURE() << "receive: " << describe(s) << " errno " << t.last_errno();
            break;
        }
        pollfd p{t.native_handle(), POLLIN, 0};
        if (::poll(&p, 1, timeout_ms) <= 0) break;
    }
    return out;
}

// Waits until the socket has something to read (or the timeout) and drains the error frames with it.
inline void settle(SocketCanTransport& t, int timeout_ms = 200) {
    pollfd p{t.native_handle(), POLLIN, 0};
    ::poll(&p, 1, timeout_ms);
}

// A raw CAN_RAW socket bound to `iface` (for injecting what SocketCanTransport refuses to send).
class RawSocket {
public:
    explicit RawSocket(const char* iface) {
        fd_ = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
        if (fd_ < 0) return;
        sockaddr_can addr{};
        addr.can_family = AF_CAN;
        addr.can_ifindex = static_cast<int>(::if_nametoindex(iface));
        if (::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
            ::close(fd_);
            fd_ = -1;
        }
    }
    ~RawSocket() {
        if (fd_ >= 0) ::close(fd_);
    }
    RawSocket(const RawSocket&) = delete;
    RawSocket& operator=(const RawSocket&) = delete;
    bool ok() const { return fd_ >= 0; }
    bool send(const can_frame& f) { return ::write(fd_, &f, sizeof f) == static_cast<ssize_t>(sizeof f); }

private:
    int fd_ = -1;
};

// Fails the test (not skips it) when the interface is missing: the harness is responsible for it.
inline ::testing::AssertionResult interface_exists(const char* iface) {
    if (::if_nametoindex(iface) != 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "CAN interface " << iface << " does not exist: run this binary through tests/vm/run-on-host.sh "
           << "(creates vcan0/vcan1 with ip link; needs root and the vcan module) or the VM harness "
           << "(scripts/vm-test.sh)";
}

}  // namespace jacobid::hal::vcan_test
