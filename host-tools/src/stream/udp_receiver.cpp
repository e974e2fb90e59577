// SPDX-License-Identifier: MIT
#include "stream/udp_receiver.hpp"

#include <arpa/inet.h>
#include <fmt/core.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "core/errors.hpp"

namespace jacobid::stream {

Endpoint parse_endpoint(const std::string& text, const std::string& option) {
    const std::size_t colon = text.rfind(':');
    const auto bad = [&](const std::string& why) { return InputError(fmt::format("{} '{}': {} (expected HOST:PORT, e.g. 127.0.0.1:5005)", option, text, why)); };
    if (colon == std::string::npos) throw bad("no ':PORT'");
    Endpoint e;
    e.host = text.substr(0, colon);
    const std::string port = text.substr(colon + 1);
    if (e.host.empty()) throw bad("empty host");
    // The estimate stream is IPv4 (AF_INET): an IPv6 address is a wrong host, not an unresolvable one.
    if (e.host.front() == '[' || e.host.find(':') != std::string::npos) throw bad("an IPv6 address; the stream is IPv4: give an IPv4 address or a host name");
    if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos) throw bad("port is not a number");
    const unsigned long value = std::stoul(port);
    if (value > 65535) throw bad("port above 65535");
    e.port = static_cast<std::uint16_t>(value);
    return e;
}

UdpReceiver::UdpReceiver(const Endpoint& endpoint) {
    addrinfo hints{};
    hints.ai_family = AF_INET;
    hints.ai_socktype = SOCK_DGRAM;
    hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
    addrinfo* found = nullptr;
    const std::string port = std::to_string(endpoint.port);
    const int rc = getaddrinfo(endpoint.host.c_str(), port.c_str(), &hints, &found);
    if (rc != 0) throw InputError(fmt::format("--udp {}:{}: cannot resolve the host ({})", endpoint.host, endpoint.port, gai_strerror(rc)));
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) {
        freeaddrinfo(found);
        throw InputError(fmt::format("--udp: cannot create a UDP socket ({})", std::strerror(errno)));
    }
    // A large receive buffer absorbs bursts while the recorder writes the file (1 kHz x 136 B is little,
    // but a slow disk or a stopped terminal can stall us for a while). The kernel caps it at rmem_max.
    const int bytes = 8 << 20;
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &bytes, sizeof bytes);
    if (::bind(fd_, found->ai_addr, found->ai_addrlen) != 0) {
        const int err = errno;
        freeaddrinfo(found);
        ::close(fd_);
        fd_ = -1;
        throw InputError(fmt::format("--udp {}:{}: cannot bind ({})", endpoint.host, endpoint.port, std::strerror(err)));
    }
    freeaddrinfo(found);
    sockaddr_in bound{};
    socklen_t length = sizeof bound;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&bound), &length);
    port_ = ntohs(bound.sin_port);
    char text[INET_ADDRSTRLEN] = {};
    ::inet_ntop(AF_INET, &bound.sin_addr, text, sizeof text);
    address_ = text;
}

UdpReceiver::~UdpReceiver() {
    if (fd_ >= 0) ::close(fd_);
}

bool UdpReceiver::receive(std::vector<std::uint8_t>& buffer, std::size_t& full_size, int timeout_ms) {
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, timeout_ms);
    if (ready <= 0) return false;  // timeout, or EINTR (the caller checks its stop flag)
    buffer.resize(buffer.capacity());
    // MSG_TRUNC: the return value is the datagram's real length even when it did not fit.
    const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), MSG_TRUNC);
    if (n < 0) return false;
    full_size = static_cast<std::size_t>(n);
    buffer.resize(std::min(full_size, buffer.size()));
    return true;
}

}  // namespace jacobid::stream
