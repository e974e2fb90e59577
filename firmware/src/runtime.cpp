// SPDX-License-Identifier: MIT
#include "jacobid/firmware/runtime.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace jacobid::firmware {

UdpPublisher::~UdpPublisher() {
    if (fd_ >= 0) ::close(fd_);
}

std::string UdpPublisher::open(const std::string& host, std::uint16_t port) {
    addrinfo hints{};
    hints.ai_family = AF_INET;
    hints.ai_socktype = SOCK_DGRAM;
    addrinfo* found = nullptr;
    const std::string service = std::to_string(port);
    if (const int rc = ::getaddrinfo(host.c_str(), service.c_str(), &hints, &found); rc != 0) {
        return "stream.host '" + host + "': " + ::gai_strerror(rc);
    }
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) {
        ::freeaddrinfo(found);
        return std::string("UDP socket: ") + std::strerror(errno);
    }
    const int rc = ::connect(fd_, found->ai_addr, found->ai_addrlen);
    const int err = errno;
    ::freeaddrinfo(found);
    if (rc != 0) return "stream " + host + ":" + service + ": connect: " + std::strerror(err);
    return {};
}

bool UdpPublisher::publish(Span<const std::uint8_t> datagram) noexcept {
    if (fd_ < 0) return false;
    const ssize_t n = ::send(fd_, datagram.data(), datagram.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
    if (n == static_cast<ssize_t>(datagram.size())) return true;
    last_errno_ = n < 0 ? errno : EMSGSIZE;
    return false;
}

FilePublisher::~FilePublisher() {
    if (fd_ >= 0) {
        flush();
        ::close(fd_);
    }
}

std::string FilePublisher::open(const std::string& path) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd_ < 0) return "stream.log " + path + ": " + std::strerror(errno);
    buffer_.assign(64 * 1024, 0);
    used_ = 0;
    return {};
}

bool FilePublisher::flush() noexcept {
    std::size_t done = 0;
    while (done < used_) {
        const ssize_t n = ::write(fd_, buffer_.data() + done, used_ - done);
        if (n <= 0) {
            if (n < 0 && errno == EINTR) continue;
            used_ = 0;
            return false;
        }
        done += static_cast<std::size_t>(n);
    }
    used_ = 0;
    return true;
}

bool FilePublisher::publish(Span<const std::uint8_t> datagram) noexcept {
    if (fd_ < 0 || datagram.size() > buffer_.size()) return false;
    bool ok = true;
    if (used_ + datagram.size() > buffer_.size()) ok = flush();
    std::memcpy(buffer_.data() + used_, datagram.data(), datagram.size());
    used_ += datagram.size();
    return ok;
}

std::string CsvCommandLog::open(const std::string& path, std::size_t joints) {
    if (std::string e = file_.open(path); !e.empty()) return "trajectory.log " + path + e.substr(e.find(':'));
    std::string header = "t_ns,phase,stop_reason,row";
    for (std::size_t j = 1; j <= joints; ++j) {
        const std::string n = std::to_string(j);
        header += ",q" + n + ",q_cmd" + n + ",qd_cmd" + n + ",tau_cmd" + n;
    }
    header += '\n';
    if (!file_.publish(Span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(header.data()), header.size()))) return "trajectory.log " + path + ": write failed";
    return {};
}

void CsvCommandLog::record(const CommandRecord& r) noexcept {
    char line[96 + kMaxJoints * 4 * 26];
    int n = std::snprintf(line, sizeof line, "%lld,%s,%s,%zu", static_cast<long long>(r.time_ns), to_string(r.phase), to_string(r.reason), r.row);
    for (std::size_t j = 0; j < r.joints && n > 0 && static_cast<std::size_t>(n) < sizeof line; ++j) {
        n += std::snprintf(line + n, sizeof line - static_cast<std::size_t>(n), ",%.17g,%.17g,%.17g,%.17g", r.measured[j], r.position[j], r.velocity[j],
                           r.torque[j]);
    }
    if (n <= 0 || static_cast<std::size_t>(n) + 1 >= sizeof line) {
        ++failures_;
        return;
    }
    line[n++] = '\n';
    if (!file_.publish(Span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(line), static_cast<std::size_t>(n)))) ++failures_;
}

RealtimeOutcome apply_realtime(const RealtimeConfig& config) {
    RealtimeOutcome r;
    if (config.lock_memory) {
        if (::mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
            r.locked = true;
        } else {
            r.warnings.push_back(std::string("mlockall refused (") + std::strerror(errno) +
                                 "): pages may be swapped or faulted in during the cycle; raise RLIMIT_MEMLOCK or run with CAP_IPC_LOCK");
        }
    }
    if (config.cpu >= 0) {
        cpu_set_t set;
        CPU_ZERO(&set);
        CPU_SET(config.cpu, &set);
        if (::sched_setaffinity(0, sizeof set, &set) == 0) {
            r.pinned = true;
        } else {
            r.warnings.push_back("CPU affinity to CPU " + std::to_string(config.cpu) + " refused (" + std::strerror(errno) +
                                 "): the scheduler may migrate the cycle thread");
        }
    }
    if (config.priority > 0) {
        sched_param p{};
        p.sched_priority = config.priority;
        if (::sched_setscheduler(0, SCHED_FIFO, &p) == 0) {
            r.fifo = true;
        } else {
            r.warnings.push_back("SCHED_FIFO priority " + std::to_string(config.priority) + " refused (" + std::strerror(errno) +
                                 "): running with the normal scheduler, expect larger jitter; needs CAP_SYS_NICE or an rtprio limit");
        }
    }
    return r;
}

const char* format_jitter(const JitterStats& s, std::uint64_t overruns, char* buffer, std::size_t size) noexcept {
    std::snprintf(buffer, size, "latency us: min %.1f avg %.1f max %.1f p99 %.0f (%llu cycles, %llu overruns)", s.min_us(), s.avg_us(),
                  s.max_us(), s.percentile_us(0.99), static_cast<unsigned long long>(s.count()), static_cast<unsigned long long>(overruns));
    return buffer;
}

const char* format_counters(const CycleCounters& c, std::size_t joints, char* buffer, std::size_t size) noexcept {
    auto u = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
    int n = std::snprintf(buffer, size,
                          "cycles %llu, datagrams %llu (publish failures %llu), frames %llu decoded %llu, rejected: short %llu "
                          "out-of-range %llu unknown-id %llu malformed %llu; duplicates %llu (conflicting %llu); CAN error frames %llu "
                          "(last class 0x%x), rx overflows %llu; SYNC sent %llu (failures %llu); e-stop events %llu (rows %llu); warm-up rows %llu",
                          u(c.cycles), u(c.datagrams_published), u(c.publish_failures), u(c.decode.frames), u(c.decode.decoded),
                          u(c.decode.rejected_short), u(c.decode.rejected_out_of_range), u(c.decode.rejected_unknown_id),
                          u(c.decode.rejected_malformed), u(c.duplicate_frames), u(c.conflicting_duplicates), u(c.can.error_frames),
                          c.can.last_error_class, u(c.can.rx_overflows), u(c.sync_sent), u(c.sync_failures), u(c.estop_events), u(c.estop_rows), u(c.warmup_rows));
    for (std::size_t j = 0; j < joints && n > 0 && static_cast<std::size_t>(n) < size; ++j) {
        const JointCounters& jc = c.joints[j];
        n += std::snprintf(buffer + n, size - static_cast<std::size_t>(n), "; j%zu stale %llu decode-error %llu dup %llu window-stale %llu",
                           j + 1, u(jc.stale_samples), u(jc.decode_error_samples), u(jc.duplicate_frames + jc.conflicting_duplicates),
                           u(jc.window_stale_rows));
    }
    return buffer;
}

const char* format_playback(const TrajectoryPlayer& p, const CycleCounters& c, char* buffer, std::size_t size) noexcept {
    auto u = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
    char stopped[96] = "";
    if (p.phase() == PlaybackPhase::Stopped) {
        if (p.stop_joint() >= 0) std::snprintf(stopped, sizeof stopped, " (stopped: %s, joint %d)", to_string(p.stop_reason()), p.stop_joint() + 1);
        else std::snprintf(stopped, sizeof stopped, " (stopped: %s)", to_string(p.stop_reason()));
    }
    std::snprintf(buffer, size, "playback: %s%s, row %zu of %zu, %llu cycles, %llu command frames (failures %llu), %llu stop cycles",
                  to_string(p.phase()), stopped, p.row() + 1, p.config().rows.size(), u(p.cycles()), u(c.command_frames), u(c.command_failures),
                  u(c.stop_cycles));
    return buffer;
}

const char* format_monitor(const FirmwareCycle& cycle, char* buffer, std::size_t size) noexcept {
    const CycleCounters& c = cycle.counters();
    auto u = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
    char joint[32] = "";
    if (cycle.contact_joint() >= 0) std::snprintf(joint, sizeof joint, ", first on joint %d", cycle.contact_joint() + 1);
    std::snprintf(buffer, size, "monitor: %llu contact events (%llu rows), acted on %llu rows%s", u(c.contact_events), u(c.contact_rows),
                  u(c.contact_stops), joint);
    return buffer;
}

}  // namespace jacobid::firmware
