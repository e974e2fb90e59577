// SPDX-License-Identifier: MIT
#pragma once
// Test side of the estimate stream: datagrams with known values, a UDP sender to 127.0.0.1, and a child
// process for `jacobid record` whose stderr we can watch (to learn the port it bound) and signal.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "jacobid/stream/estimate_datagram.hpp"

namespace jacobid::test {

using Datagram = jacobid::stream::EstimateDatagram<8>;
constexpr std::int64_t kStartNs = 1700000000000000000;  // a present-day epoch time
constexpr std::int64_t kPeriodNs = 1000000;              // 1 kHz

// Values that identify their sequence number and joint, exactly representable after %.17g.
inline double q_of(std::uint64_t seq, std::size_t j) { return std::sin(0.001 * static_cast<double>(seq) + static_cast<double>(j)); }
inline double tau_of(std::uint64_t seq, std::size_t j) { return 0.5 * std::cos(0.002 * static_cast<double>(seq)) - static_cast<double>(j); }

// Wake-up jitter of the controller cycle that stamped the datagram: up to 78 us, as on a real loop; the
// recorder's t must not see it (nominal sample time), its t_wake must.
inline std::int64_t wake_jitter_ns(std::uint64_t seq) { return static_cast<std::int64_t>(seq % 7) * 13'000; }

inline Datagram make_datagram(std::uint64_t seq, std::size_t joints = 2) {
    Datagram d;
    d.sequence = seq;
    d.sample_index = 5000 + seq;
    d.timestamp_ns = kStartNs + static_cast<std::int64_t>(seq) * kPeriodNs + wake_jitter_ns(seq);
    d.sample_period = 1e-3;
    d.delay_samples = 100;
    d.joint_count = joints;
    for (std::size_t j = 0; j < joints; ++j) {
        d.joints[j] = {q_of(seq, j), q_of(seq, j) + 1e-4, 10.0 + static_cast<double>(seq), -static_cast<double>(seq), tau_of(seq, j), 0};
    }
    return d;
}

inline std::vector<std::uint8_t> encode_bytes(const Datagram& d) {
    std::vector<std::uint8_t> b(jacobid::stream::datagram_size(d.joint_count, d.version));
    std::size_t written = 0;
    if (jacobid::stream::encode(d, jacobid::Span<std::uint8_t>(b), written) != jacobid::stream::DatagramStatus::Ok) {
        throw std::runtime_error("test datagram does not encode");
    }
    return b;
}

class UdpSender {
public:
    explicit UdpSender(int port) : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
        to_.sin_family = AF_INET;
        to_.sin_port = htons(static_cast<std::uint16_t>(port));
        to_.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    }
    ~UdpSender() { ::close(fd_); }
    UdpSender(const UdpSender&) = delete;
    UdpSender& operator=(const UdpSender&) = delete;
    void send(const std::vector<std::uint8_t>& bytes) {
        if (::sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to_), sizeof to_) != static_cast<ssize_t>(bytes.size())) {
            throw std::runtime_error("sendto failed");
        }
        // Loopback does not drop unless the receiver's buffer overflows; a short pause every few
        // datagrams keeps the test far from that without making it slow.
        if (++sent_ % 16 == 0) std::this_thread::sleep_for(std::chrono::microseconds(300));
    }
    void send(const Datagram& d) { send(encode_bytes(d)); }
    std::size_t sent() const { return sent_; }

private:
    int fd_;
    sockaddr_in to_{};
    std::size_t sent_ = 0;
};

inline std::string slurp_file(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// `jacobid record ...` as a child process (no shell), stdout/stderr to files.
class Recorder {
public:
    Recorder(const std::vector<std::string>& args, const std::string& stderr_path) : err_path_(stderr_path) {
        pid_ = ::fork();
        if (pid_ == 0) {
            const int err = ::open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            const int out = ::open("/dev/null", O_WRONLY);
            ::dup2(err, 2);
            ::dup2(out, 1);
            std::vector<char*> argv;
            std::string exe = JACOBID_EXECUTABLE;
            argv.push_back(exe.data());
            std::vector<std::string> copy = args;
            for (auto& a : copy) argv.push_back(a.data());
            argv.push_back(nullptr);
            ::execv(exe.c_str(), argv.data());
            ::_exit(127);
        }
    }
    ~Recorder() {
        if (pid_ > 0 && exit_code_ == -2) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
    }
    Recorder(const Recorder&) = delete;
    Recorder& operator=(const Recorder&) = delete;

    // Waits for "listening on 127.0.0.1:PORT" and returns PORT (throws if the recorder exits first or after 10 s).
    int wait_for_port() {
        const std::string marker = "listening on 127.0.0.1:";
        int port = -1;
        const bool found = wait_for_err([&](const std::string& err) {
            const std::size_t at = err.find(marker);
            if (at == std::string::npos || err.find('\n', at) == std::string::npos) return false;
            port = std::stoi(err.substr(at + marker.size()));
            return true;
        }, 10.0);
        if (found) return port;
        if (exit_code_ != -2) throw std::runtime_error("jacobid record exited before listening: " + err());
        throw std::runtime_error("jacobid record did not start listening");
    }
    void signal(int sig) { ::kill(pid_, sig); }
    // Waits until a progress line ("record: S s, N datagrams, ...", once a second without --quiet) counts
    // at least `datagrams`; false if the recorder exits first or after `timeout_s`.
    bool wait_for_received(std::size_t datagrams, double timeout_s = 10.0) {
        return wait_for_err([&](const std::string& err) {
            for (std::size_t at = err.find(" s, "); at != std::string::npos; at = err.find(" s, ", at + 1)) {
                const std::size_t line_end = err.find('\n', at);
                if (line_end == std::string::npos) break;  // a line still being written
                const std::size_t digits = err.find_first_not_of("0123456789", at + 4);
                if (digits == at + 4 || err.compare(digits, 11, " datagrams,") != 0) continue;
                if (std::stoull(err.substr(at + 4, digits - at - 4)) >= datagrams) return true;
            }
            return false;
        }, timeout_s);
    }
    // Exit code (-1 if killed by a signal); kills the child after `timeout_s`.
    int wait(double timeout_s = 10.0) {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
        while (exit_code_ == -2) {
            int status = 0;
            if (::waitpid(pid_, &status, WNOHANG) == pid_) {
                exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
            } else if (std::chrono::steady_clock::now() > end) {
                ::kill(pid_, SIGKILL);
                ::waitpid(pid_, nullptr, 0);
                exit_code_ = -1;
            } else {
                std::this_thread::sleep_for(std::chrono::milliseconds(5));
            }
        }
        return exit_code_;
    }
    std::string err() const { return slurp_file(err_path_); }

private:
    // Polls the recorder's stderr (every 10 ms) until `found` says what it waits for is there: true; false when the
    // recorder exits first (exit_code_ set) or after `timeout_s`. The one wait both waits above share.
    template <typename Found>
    bool wait_for_err(Found found, double timeout_s) {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
        while (std::chrono::steady_clock::now() < end) {
            if (found(slurp_file(err_path_))) return true;
            int status = 0;
            if (::waitpid(pid_, &status, WNOHANG) == pid_) {
                exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
                return false;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        return false;
    }

    pid_t pid_ = -1;
    int exit_code_ = -2;  // -2: still running
    std::string err_path_;
};

}  // namespace jacobid::test
