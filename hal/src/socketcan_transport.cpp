// SPDX-License-Identifier: MIT
// SocketCAN backend. See socketcan_transport.hpp for the contract; comments here explain the system
// call details.
#include "jacobid/hal/socketcan_transport.hpp"

#include <linux/can/error.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>

namespace jacobid::hal {

can_filter to_kernel_filter(const CanFilter& filter) noexcept {
    can_filter k{};
    const bool extended = filter.format == CanIdFormat::Extended;
    const std::uint32_t id_mask = extended || filter.format == CanIdFormat::Any ? CAN_EFF_MASK : CAN_SFF_MASK;
    k.can_id = (filter.id & id_mask) | (extended ? CAN_EFF_FLAG : 0u);
    k.can_mask = filter.mask & id_mask;
    if (filter.format != CanIdFormat::Any) k.can_mask |= CAN_EFF_FLAG;
    if (!filter.accept_remote) k.can_mask |= CAN_RTR_FLAG;  // filter id has RTR clear: data frames only
    return k;
}

CanStatus to_kernel(const CanFrame& frame, canfd_frame& out, std::size_t& wire_size) noexcept {
    if (!is_valid_frame(frame) || frame.error()) return CanStatus::InvalidFrame;
    out = canfd_frame{};
    out.can_id = frame.id | (frame.extended() ? CAN_EFF_FLAG : 0u) | (frame.remote() ? CAN_RTR_FLAG : 0u);
    out.len = frame.len;
    if (frame.fd()) {
        // FDF marks the structure as FD for kernels with CAN XL support; older ones ignore it.
        out.flags = static_cast<std::uint8_t>(CANFD_FDF | ((frame.flags & kCanBitRateSwitch) ? CANFD_BRS : 0) |
                                              ((frame.flags & kCanErrorStateIndicator) ? CANFD_ESI : 0));
        wire_size = CANFD_MTU;
    } else {
        wire_size = CAN_MTU;  // struct can_frame is the first CAN_MTU bytes of canfd_frame
    }
    if (!frame.remote()) std::memcpy(out.data, frame.data.data(), frame.len);
    return CanStatus::Ok;
}

KernelFrameKind from_kernel(const canfd_frame& in, std::size_t nbytes, CanFrame& out) noexcept {
    const bool fd = nbytes == CANFD_MTU;
    if (!fd && nbytes != CAN_MTU) return KernelFrameKind::Invalid;
    if (in.can_id & CAN_ERR_FLAG) {
        out = CanFrame{};
        out.id = in.can_id & CAN_ERR_MASK;
        out.flags = kCanError;
        out.len = in.len <= CAN_MAX_DLEN ? in.len : static_cast<std::uint8_t>(CAN_MAX_DLEN);
        std::memcpy(out.data.data(), in.data, out.len);
        return KernelFrameKind::Error;
    }
    if (fd ? !is_valid_fd_length(in.len) : in.len > CAN_MAX_DLEN) return KernelFrameKind::Invalid;
    out.flags = 0;
    if (in.can_id & CAN_EFF_FLAG) {
        out.id = in.can_id & CAN_EFF_MASK;
        out.flags |= kCanExtended;
    } else {
        out.id = in.can_id & CAN_SFF_MASK;
    }
    if (fd) {
        out.flags |= kCanFd;
        if (in.flags & CANFD_BRS) out.flags |= kCanBitRateSwitch;
        if (in.flags & CANFD_ESI) out.flags |= kCanErrorStateIndicator;
    } else if (in.can_id & CAN_RTR_FLAG) {
        out.flags |= kCanRemote;
    }
    out.len = in.len;
    std::memcpy(out.data.data(), in.data, in.len);
    // Stale bytes beyond len would make frames with equal content compare unequal in tests and logs.
    std::memset(out.data.data() + in.len, 0, out.data.size() - in.len);
    return KernelFrameKind::Data;
}

ReceiveControl parse_receive_control(const msghdr& msg) noexcept {
    ReceiveControl rc;
    // CMSG_NXTHDR takes a non-const msghdr on glibc although it does not modify it.
    auto& m = const_cast<msghdr&>(msg);
    for (cmsghdr* c = CMSG_FIRSTHDR(&m); c != nullptr; c = CMSG_NXTHDR(&m, c)) {
        if (c->cmsg_level != SOL_SOCKET) continue;
        const std::size_t payload = c->cmsg_len - CMSG_LEN(0);
        if (c->cmsg_type == SCM_TIMESTAMPNS && payload >= sizeof(timespec)) {
            timespec ts{};
            std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
            rc.has_timestamp = true;
            rc.timestamp_ns = static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + static_cast<std::int64_t>(ts.tv_nsec);
        } else if (c->cmsg_type == SO_RXQ_OVFL && payload >= sizeof(std::uint32_t)) {
            std::memcpy(&rc.drop_count, CMSG_DATA(c), sizeof rc.drop_count);
            rc.has_drop_count = true;
        }
    }
    return rc;
}

SocketCanTransport::~SocketCanTransport() { close(); }

void SocketCanTransport::close() noexcept {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

CanStatus SocketCanTransport::fail_open(CanStatus s, int err) noexcept {
    last_errno_ = err;
    close();
    return s;
}

CanStatus SocketCanTransport::adopt(int fd, bool fd_frames) noexcept {
    if (fd_ >= 0) return CanStatus::AlreadyOpen;
    if (fd < 0) return CanStatus::NotOpen;
    fd_ = fd;
    fd_frames_ = fd_frames;
    counters_ = CanCounters{};
    overflow_base_ = 0;
    last_drop_count_ = 0;
    last_errno_ = 0;
    return CanStatus::Ok;
}

CanStatus SocketCanTransport::open(const SocketCanConfig& config) noexcept {
    if (fd_ >= 0) return CanStatus::AlreadyOpen;
    last_errno_ = 0;
    // Checked before any system call so that a configuration error reads as one on every kernel.
    const std::size_t name_len = config.interface ? ::strnlen(config.interface, IFNAMSIZ) : 0;
    if (name_len == 0 || name_len >= IFNAMSIZ) return CanStatus::InvalidInterfaceName;
    if (config.filters.size() > kMaxFilters) return CanStatus::TooManyFilters;

    const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
    if (fd < 0) {
        const int err = errno;
        last_errno_ = err;
        return err == EAFNOSUPPORT || err == EPROTONOSUPPORT ? CanStatus::KernelHasNoCan : CanStatus::SocketFailed;
    }
    fd_ = fd;

    ifreq ifr{};
    std::memcpy(ifr.ifr_name, config.interface, name_len);
    if (::ioctl(fd_, SIOCGIFINDEX, &ifr) < 0) {
        const int err = errno;
        return fail_open(err == ENODEV ? CanStatus::NoSuchInterface : CanStatus::SocketOptionFailed, err);
    }
    const int ifindex = ifr.ifr_ifindex;

    auto set_int = [this](int level, int name, int value) {
        return ::setsockopt(fd_, level, name, &value, sizeof value) == 0;
    };
    if (config.fd_frames) {
        if (::ioctl(fd_, SIOCGIFMTU, &ifr) < 0) return fail_open(CanStatus::SocketOptionFailed, errno);
        if (ifr.ifr_mtu < static_cast<int>(CANFD_MTU)) return fail_open(CanStatus::FdNotSupported, 0);
        if (!set_int(SOL_CAN_RAW, CAN_RAW_FD_FRAMES, 1)) return fail_open(CanStatus::SocketOptionFailed, errno);
    }
    if (!config.filters.empty()) {
        for (std::size_t i = 0; i < config.filters.size(); ++i) kernel_filters_[i] = to_kernel_filter(config.filters[i]);
        const auto bytes = static_cast<socklen_t>(config.filters.size() * sizeof(can_filter));
        if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, kernel_filters_.data(), bytes) != 0)
            return fail_open(CanStatus::SocketOptionFailed, errno);
    }
    const can_err_mask_t err_mask = config.error_frames ? CAN_ERR_MASK : 0;
    if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) != 0)
        return fail_open(CanStatus::SocketOptionFailed, errno);
    if (config.receive_own && !set_int(SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, 1))
        return fail_open(CanStatus::SocketOptionFailed, errno);
    if (!set_int(SOL_SOCKET, SO_TIMESTAMPNS, 1)) return fail_open(CanStatus::SocketOptionFailed, errno);
    if (!set_int(SOL_SOCKET, SO_RXQ_OVFL, 1)) return fail_open(CanStatus::SocketOptionFailed, errno);
    if (config.receive_buffer_bytes > 0 && !set_int(SOL_SOCKET, SO_RCVBUF, config.receive_buffer_bytes))
        return fail_open(CanStatus::SocketOptionFailed, errno);

    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifindex;
    if (::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) return fail_open(CanStatus::BindFailed, errno);

    fd_frames_ = config.fd_frames;
    counters_ = CanCounters{};
    overflow_base_ = 0;
    last_drop_count_ = 0;
    return CanStatus::Ok;
}

CanStatus SocketCanTransport::send(const CanFrame& frame) noexcept {
    if (fd_ < 0) return CanStatus::NotOpen;
    if (frame.fd() && !fd_frames_) return CanStatus::FdNotEnabled;
    canfd_frame k;
    std::size_t size = 0;
    if (to_kernel(frame, k, size) != CanStatus::Ok) return CanStatus::InvalidFrame;
    for (;;) {
        const ssize_t n = ::send(fd_, &k, size, MSG_DONTWAIT | MSG_NOSIGNAL);
        if (n == static_cast<ssize_t>(size)) {
            ++counters_.tx_frames;
            return CanStatus::Ok;
        }
        if (n < 0 && errno == EINTR) continue;
        // A full device queue shows as ENOBUFS on CAN even for non-blocking sockets, a full socket send
        // buffer as EAGAIN: both mean "the bus is saturated", not a fault of the socket.
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS)) {
            ++counters_.tx_queue_full;
            return CanStatus::TxQueueFull;
        }
        last_errno_ = n < 0 ? errno : EIO;
        ++counters_.io_errors;
        return CanStatus::IoError;
    }
}

CanStatus SocketCanTransport::receive(CanFrame& frame) noexcept {
    if (fd_ < 0) return CanStatus::NotOpen;
    for (;;) {
        iovec iov{&rx_frame_, sizeof rx_frame_};
        msghdr msg{};
        msg.msg_iov = &iov;
        msg.msg_iovlen = 1;
        msg.msg_control = control_.data();
        msg.msg_controllen = control_.size();
        const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT);
        if (n < 0) {
            const int err = errno;
            if (err == EINTR) continue;
            if (err == EAGAIN || err == EWOULDBLOCK) return CanStatus::Empty;
            last_errno_ = err;
            ++counters_.io_errors;
            return CanStatus::IoError;
        }
        const ReceiveControl rc = parse_receive_control(msg);
        if (rc.has_drop_count) {
            // The socket's counter is a wrapping 32-bit total: carry the wrap into 64 bits.
            if (rc.drop_count < last_drop_count_) overflow_base_ += (1ull << 32);
            last_drop_count_ = rc.drop_count;
            counters_.rx_overflows = overflow_base_ + rc.drop_count;
        }
        if (msg.msg_flags & MSG_TRUNC) {  // larger than a canfd_frame: not a CAN_RAW frame
            ++counters_.io_errors;
            continue;
        }
        switch (from_kernel(rx_frame_, static_cast<std::size_t>(n), frame)) {
            case KernelFrameKind::Data:
                frame.timestamp_ns = rc.has_timestamp ? rc.timestamp_ns : 0;
                ++counters_.rx_frames;
                return CanStatus::Ok;
            case KernelFrameKind::Error:
                ++counters_.error_frames;
                counters_.last_error_class = frame.id;
                break;  // consumed: read on, the caller asked for a data frame
            case KernelFrameKind::Invalid:
                ++counters_.io_errors;
                break;
        }
    }
}

}  // namespace jacobid::hal
