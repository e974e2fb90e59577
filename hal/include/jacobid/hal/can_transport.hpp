// SPDX-License-Identifier: MIT
#pragma once
// The CAN transport interface the firmware cycle talks to. Two backends: SocketCanTransport (Linux
// kernel, socketcan_transport.hpp) and VirtualCanBus endpoints (in-process, virtual_can_bus.hpp).
//
// Contract for every backend, after a successful open:
//  - send() never blocks: a full transmit queue returns TxQueueFull and is counted; the caller decides
//    whether to drop or retry next cycle (a real-time loop must never wait on the bus).
//  - receive() never blocks: it returns one data frame or Empty. Error frames are consumed by the
//    transport (counted, class kept in CanCounters) and never handed to the decoders.
//  - neither allocates nor throws.
#include <cstddef>
#include <cstdint>

#include "jacobid/hal/can_frame.hpp"
#include "jacobid/span.hpp"

namespace jacobid::hal {

enum class CanStatus {
    Ok,
    Empty,                 // receive(): nothing pending (normal, not an error)
    NotOpen,               // used before a successful open()
    AlreadyOpen,           // open() on an open transport
    TxQueueFull,           // send(): the transmit queue is full; frame not sent
    InvalidFrame,          // send(): id/length/flags inconsistent (see is_valid_frame)
    FdNotEnabled,          // send(): an FD frame on a transport opened without CAN FD
    TooManyFilters,        // more acceptance filters than the backend holds
    KernelHasNoCan,        // socket(PF_CAN) failed with EAFNOSUPPORT: kernel built without CAN / can-raw
    SocketFailed,          // socket(PF_CAN) failed for another reason (see last_errno)
    InvalidInterfaceName,  // empty, or longer than IFNAMSIZ - 1
    NoSuchInterface,       // the interface does not exist
    FdNotSupported,        // CAN FD requested but the interface MTU is classic CAN
    SocketOptionFailed,    // a setsockopt failed (see last_errno)
    BindFailed,            // bind() failed (see last_errno), e.g. interface down
    IoError,               // recvmsg/sendmsg failed otherwise (see last_errno), e.g. ENETDOWN
    BusFull,               // virtual bus: every endpoint slot is in use
};

inline const char* describe(CanStatus s) noexcept {
    switch (s) {
        case CanStatus::Ok: return "ok";
        case CanStatus::Empty: return "no frame pending";
        case CanStatus::NotOpen: return "CAN transport used before a successful open()";
        case CanStatus::AlreadyOpen: return "CAN transport is already open";
        case CanStatus::TxQueueFull: return "CAN transmit queue full: frame not sent";
        case CanStatus::InvalidFrame: return "invalid CAN frame (id wider than its format, bad length or flags)";
        case CanStatus::FdNotEnabled: return "CAN FD frame on a transport opened for classic CAN";
        case CanStatus::TooManyFilters: return "more CAN acceptance filters than the transport holds";
        case CanStatus::KernelHasNoCan:
            return "this kernel has no CAN support (socket(PF_CAN) failed with EAFNOSUPPORT): load the can and can_raw modules";
        case CanStatus::SocketFailed: return "socket(PF_CAN, SOCK_RAW, CAN_RAW) failed";
        case CanStatus::InvalidInterfaceName: return "CAN interface name empty or too long";
        case CanStatus::NoSuchInterface: return "no such CAN interface";
        case CanStatus::FdNotSupported: return "CAN FD requested but the interface is classic CAN (MTU 16)";
        case CanStatus::SocketOptionFailed: return "setsockopt on the CAN socket failed";
        case CanStatus::BindFailed: return "bind() of the CAN socket to the interface failed";
        case CanStatus::IoError: return "CAN socket I/O error";
        case CanStatus::BusFull: return "virtual CAN bus has no free endpoint";
    }
    return "unknown CAN status";
}

// Transport counters, monotonic since open(). Read them every cycle (e.g. into telemetry); differences
// between two cycles tell what happened in between.
struct CanCounters {
    std::uint64_t rx_frames = 0;        // data frames handed to the caller
    std::uint64_t tx_frames = 0;        // frames accepted for transmission
    std::uint64_t error_frames = 0;     // error frames received (consumed, not handed over)
    std::uint64_t rx_overflows = 0;     // frames dropped because a receive queue was full
    std::uint64_t tx_queue_full = 0;    // send() calls refused with TxQueueFull
    std::uint64_t io_errors = 0;        // receive/send failures other than the above
    std::uint32_t last_error_class = 0; // CAN_ERR_* class bits of the last error frame (linux/can/error.h)
};

struct DrainResult {
    std::size_t count = 0;           // frames written to the output span
    CanStatus status = CanStatus::Ok;  // Ok (queue empty or span full) or the error that stopped the drain
};

class CanTransport {
public:
    virtual ~CanTransport() = default;

    virtual CanStatus send(const CanFrame& frame) noexcept = 0;
    virtual CanStatus receive(CanFrame& frame) noexcept = 0;
    virtual const CanCounters& counters() const noexcept = 0;
    virtual bool is_open() const noexcept = 0;

    // Non-blocking drain, once per cycle: receive until the queue is empty or `out` is full. Frames left
    // over stay queued for the next cycle (size `out` for a cycle's worth plus margin).
    DrainResult drain(Span<CanFrame> out) noexcept {
        DrainResult r;
        while (r.count < out.size()) {
            const CanStatus s = receive(out[r.count]);
            if (s == CanStatus::Empty) break;
            if (s != CanStatus::Ok) {
                r.status = s;
                break;
            }
            ++r.count;
        }
        return r;
    }

protected:
    CanTransport() = default;
    CanTransport(const CanTransport&) = default;
    CanTransport& operator=(const CanTransport&) = default;
};

}  // namespace jacobid::hal
