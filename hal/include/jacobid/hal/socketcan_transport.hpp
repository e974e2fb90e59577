// SPDX-License-Identifier: MIT
#pragma once
// SocketCAN backend of CanTransport (Linux raw CAN socket, CAN_RAW).
//
// open() does every system call that may allocate or sleep (socket, ioctl, setsockopt, bind); after it,
// send() and receive() are one non-blocking sendmsg/recvmsg each, into buffers owned by the object:
//  - receive timestamps: SO_TIMESTAMPNS (CLOCK_REALTIME at driver receive, not at our read), so the
//    frame time does not jitter with the cycle's scheduling;
//  - drops: SO_RXQ_OVFL puts the socket's cumulative drop count on every frame; CanCounters::rx_overflows
//    follows it, so a receive buffer too small for a cycle's burst shows up instead of passing silently;
//  - kernel acceptance filters (CAN_RAW_FILTER): frames of other devices are dropped in the kernel, not
//    copied to us every cycle;
//  - error frames (CAN_RAW_ERR_FILTER = CAN_ERR_MASK) are counted with their class bits, not handed on;
//  - a full transmit queue (EAGAIN / ENOBUFS) returns TxQueueFull instead of blocking the cycle;
//  - optional CAN FD (CAN_RAW_FD_FRAMES), refused at open() when the interface MTU is classic.
#include <linux/can.h>
#include <linux/can/raw.h>
#include <sys/socket.h>

#include <array>
#include <cstddef>
#include <cstdint>

#include "jacobid/hal/can_frame.hpp"
#include "jacobid/hal/can_transport.hpp"
#include "jacobid/span.hpp"

namespace jacobid::hal {

struct SocketCanConfig {
    const char* interface = "can0";  // copied during open()
    bool fd_frames = false;          // enable CAN FD (needs an FD-capable interface, MTU 72)
    bool error_frames = true;        // receive and count error frames
    bool receive_own = false;        // CAN_RAW_RECV_OWN_MSGS: see our own transmitted frames
    Span<const CanFilter> filters{}; // kernel acceptance filters; empty accepts everything
    int receive_buffer_bytes = 0;    // SO_RCVBUF; 0 keeps the system default
};

// --- Conversions between CanFrame and the kernel structures (pure functions, unit-tested) ---

// Kernel filter for CAN_RAW_FILTER with the semantics of matches(): the EFF flag joins the mask unless
// the filter takes Any format, the RTR flag joins it unless remote frames are accepted.
can_filter to_kernel_filter(const CanFilter& filter) noexcept;

// Fills the kernel frame for sending; `wire_size` is CAN_MTU for classic frames, CANFD_MTU for FD.
// Returns InvalidFrame for an invalid or error frame.
CanStatus to_kernel(const CanFrame& frame, canfd_frame& out, std::size_t& wire_size) noexcept;

enum class KernelFrameKind { Data, Error, Invalid };
// Reads `nbytes` bytes as received from a CAN_RAW socket: CAN_MTU = classic, CANFD_MTU = FD, anything
// else (or a length over the maximum) is Invalid. An error frame yields Error with out.id = class bits.
KernelFrameKind from_kernel(const canfd_frame& in, std::size_t nbytes, CanFrame& out) noexcept;

// What the control messages of one recvmsg carried.
struct ReceiveControl {
    bool has_timestamp = false;
    std::int64_t timestamp_ns = 0;  // SO_TIMESTAMPNS
    bool has_drop_count = false;
    std::uint32_t drop_count = 0;   // SO_RXQ_OVFL: cumulative drops of the socket
};
ReceiveControl parse_receive_control(const msghdr& msg) noexcept;

class SocketCanTransport final : public CanTransport {
public:
    static constexpr std::size_t kMaxFilters = 64;

    SocketCanTransport() noexcept = default;
    ~SocketCanTransport() override;
    SocketCanTransport(const SocketCanTransport&) = delete;
    SocketCanTransport& operator=(const SocketCanTransport&) = delete;

    // Opens and configures the raw socket. On failure nothing stays open; last_errno() has the cause.
    CanStatus open(const SocketCanConfig& config) noexcept;
    // Takes ownership of an already configured datagram socket (one handed over by a supervisor, or a
    // socketpair in tests) and uses it as is: no option is set, so no timestamps unless the owner set them.
    CanStatus adopt(int fd, bool fd_frames) noexcept;
    void close() noexcept;

    CanStatus send(const CanFrame& frame) noexcept override;
    CanStatus receive(CanFrame& frame) noexcept override;
    const CanCounters& counters() const noexcept override { return counters_; }
    bool is_open() const noexcept override { return fd_ >= 0; }

    int last_errno() const noexcept { return last_errno_; }
    int native_handle() const noexcept { return fd_; }  // for poll/epoll by an event loop

private:
    CanStatus fail_open(CanStatus s, int err) noexcept;

    int fd_ = -1;
    bool fd_frames_ = false;
    int last_errno_ = 0;
    CanCounters counters_{};
    std::uint64_t overflow_base_ = 0;  // drops seen before the socket's counter restarted
    std::uint32_t last_drop_count_ = 0;
    canfd_frame rx_frame_{};
    // Room for a timestamp and a drop count (and slack for a 64-bit timespec variant).
    alignas(cmsghdr) std::array<unsigned char, 128> control_{};
    std::array<can_filter, kMaxFilters> kernel_filters_{};
};

}  // namespace jacobid::hal
