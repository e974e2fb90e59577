// SPDX-License-Identifier: MIT
#pragma once
// The operating-system side of jacobid-fw: UDP and file publishers, real-time settings, summary lines.
// Everything here is set up at start-up (may allocate); the per-cycle calls (publish, format_*) do not.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "jacobid/fwconfig/firmware_config.hpp"
#include "jacobid/firmware/firmware_cycle.hpp"
#include "jacobid/firmware/jitter_stats.hpp"

namespace jacobid::firmware {

// Connected, non-blocking IPv4 UDP socket: publish() is one send(MSG_DONTWAIT); a full socket buffer or
// an ICMP "port unreachable" (nobody recording yet) is a failed publish, counted, never waited on.
class UdpPublisher final : public Publisher {
public:
    UdpPublisher() = default;
    ~UdpPublisher() override;
    UdpPublisher(const UdpPublisher&) = delete;
    UdpPublisher& operator=(const UdpPublisher&) = delete;
    // Resolves host (name or dotted quad) and connects. Returns "" or a one-line reason.
    std::string open(const std::string& host, std::uint16_t port);
    bool publish(Span<const std::uint8_t> datagram) noexcept override;
    int last_errno() const noexcept { return last_errno_; }

private:
    int fd_ = -1;
    int last_errno_ = 0;
};

// Local log: the datagrams back to back (each one's size follows from its header). Buffered in a fixed
// block written with one write() when full, so the cycle pays a syscall every ~64 KB, not every cycle.
class FilePublisher final : public Publisher {
public:
    FilePublisher() = default;
    ~FilePublisher() override;
    FilePublisher(const FilePublisher&) = delete;
    FilePublisher& operator=(const FilePublisher&) = delete;
    std::string open(const std::string& path);
    bool publish(Span<const std::uint8_t> datagram) noexcept override;
    bool flush() noexcept;

private:
    int fd_ = -1;
    std::vector<std::uint8_t> buffer_;  // sized once in open()
    std::size_t used_ = 0;
};

// trajectory.log: the CommandLog as CSV, one row per playback cycle (t_ns, phase, stop_reason, row, then
// per joint q<j> measured and q_cmd<j>, qd_cmd<j>, tau_cmd<j> sent), formatted with snprintf into a fixed
// line and written through a FilePublisher's buffer (a syscall every ~64 KB).
class CsvCommandLog final : public CommandLog {
public:
    std::string open(const std::string& path, std::size_t joints);
    void record(const CommandRecord& r) noexcept override;
    bool flush() noexcept { return file_.flush(); }
    std::uint64_t failures() const noexcept { return failures_; }

private:
    FilePublisher file_;
    std::uint64_t failures_ = 0;  // rows that did not fit the line or the file
};

// Hands every datagram to up to two publishers; succeeds when the first (the stream) did.
class TeePublisher final : public Publisher {
public:
    TeePublisher(Publisher& primary, Publisher* secondary) noexcept : primary_(primary), secondary_(secondary) {}
    bool publish(Span<const std::uint8_t> datagram) noexcept override {
        if (secondary_ != nullptr) secondary_failures_ += secondary_->publish(datagram) ? 0u : 1u;
        return primary_.publish(datagram);
    }
    std::uint64_t secondary_failures() const noexcept { return secondary_failures_; }

private:
    Publisher& primary_;
    Publisher* secondary_;
    std::uint64_t secondary_failures_ = 0;
};

// SCHED_FIFO, mlockall and CPU affinity as configured. Each one that is refused (EPERM in a container,
// no CAP_SYS_NICE, ...) yields a warning line and the firmware runs on without it.
struct RealtimeOutcome {
    bool fifo = false, locked = false, pinned = false;
    std::vector<std::string> warnings;
};
RealtimeOutcome apply_realtime(const RealtimeConfig& config);

// One line each, into a caller's buffer (snprintf: no allocation). Return the buffer.
const char* format_jitter(const JitterStats& s, std::uint64_t overruns, char* buffer, std::size_t size) noexcept;
const char* format_counters(const CycleCounters& c, std::size_t joints, char* buffer, std::size_t size) noexcept;
// "playback: <phase> [(stopped: <reason>, joint N)], row R, C cycles, F command frames (failures X), S stop cycles".
const char* format_playback(const TrajectoryPlayer& p, const CycleCounters& c, char* buffer, std::size_t size) noexcept;
// "monitor: 2 contact events (35 rows), acted on 35 rows, first on joint 3"
const char* format_monitor(const FirmwareCycle& cycle, char* buffer, std::size_t size) noexcept;

}  // namespace jacobid::firmware
