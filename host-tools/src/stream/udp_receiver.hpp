// SPDX-License-Identifier: MIT
#pragma once
// A bound IPv4 UDP socket for the estimate stream (plain POSIX sockets). Host tools only.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace jacobid::stream {

struct Endpoint {
    std::string host;        // name or dotted quad; "0.0.0.0" listens on every interface
    std::uint16_t port = 0;  // 0 = any free port (see UdpReceiver::port())
};

// "HOST:PORT" (e.g. "127.0.0.1:5005", "0.0.0.0:5005", "localhost:0"); InputError naming `option` when malformed.
Endpoint parse_endpoint(const std::string& text, const std::string& option);

class UdpReceiver {
public:
    // Resolves and binds; InputError naming the endpoint and the system's reason when that fails.
    explicit UdpReceiver(const Endpoint& endpoint);
    ~UdpReceiver();
    UdpReceiver(const UdpReceiver&) = delete;
    UdpReceiver& operator=(const UdpReceiver&) = delete;

    std::uint16_t port() const { return port_; }         // the bound port, also when 0 was asked for
    const std::string& address() const { return address_; }  // the bound address, dotted quad

    // Waits up to timeout_ms for one datagram and copies it into `buffer` (resized to the datagram's
    // length; a datagram longer than the buffer's capacity keeps its true length in `full_size`, so it can
    // be reported as oversized instead of being silently cut). Returns false on timeout or on a signal.
    bool receive(std::vector<std::uint8_t>& buffer, std::size_t& full_size, int timeout_ms);

private:
    int fd_ = -1;
    std::uint16_t port_ = 0;
    std::string address_;
};

}  // namespace jacobid::stream
