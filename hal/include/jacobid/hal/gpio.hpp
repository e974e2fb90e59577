// SPDX-License-Identifier: MIT
#pragma once
// Safety GPIO logic: drive-enable output, e-stop input (active-low, latched), cycle-sync output.
//
// The logic talks to two tiny line interfaces so that it is tested with fake lines; gpiod_lines.hpp
// implements them with libgpiod. Rules, each because a stop must never be missed or undone by itself:
//  - the e-stop input is read first in every cycle, so a press drops the enable in the same cycle;
//  - a stop latches: it stays until reset_estop() is called while the input reads released;
//  - a failed read counts as a stop (a broken wire or a lost chip must not look like "released");
//  - a failed write of the enable line latches a stop too: its level is then unknown;
//  - after any stop the enable request must go false once before the drive is enabled again (no
//    automatic restart when a latch is reset while the firmware still asks for enable);
//  - the sync output toggles once per cycle, so a scope or a logic analyser sees the cycle period and
//    its jitter; a failed sync write is only counted.
#include <cstdint>

namespace jacobid::hal {

enum class GpioStatus {
    Ok,
    NotOpen,        // line used before a successful open()
    ChipNotFound,   // gpiod_chip_open_lookup failed (no such chip; this machine has no GPIO)
    LineNotFound,   // offset beyond the chip's lines
    RequestFailed,  // the line is busy (requested by another consumer) or the request was refused
    ReadFailed,
    WriteFailed,
};

inline const char* describe(GpioStatus s) noexcept {
    switch (s) {
        case GpioStatus::Ok: return "ok";
        case GpioStatus::NotOpen: return "GPIO line used before a successful open()";
        case GpioStatus::ChipNotFound: return "GPIO chip not found";
        case GpioStatus::LineNotFound: return "GPIO line offset not found on the chip";
        case GpioStatus::RequestFailed: return "GPIO line request refused (busy or not permitted)";
        case GpioStatus::ReadFailed: return "GPIO line read failed";
        case GpioStatus::WriteFailed: return "GPIO line write failed";
    }
    return "unknown GPIO status";
}

// Physical levels (true = high), before any active-low inversion: the logic owns the polarity.
class InputLine {
public:
    virtual ~InputLine() = default;
    virtual GpioStatus read(bool& level) noexcept = 0;
};
class OutputLine {
public:
    virtual ~OutputLine() = default;
    virtual GpioStatus write(bool level) noexcept = 0;
};

enum class StopCause : std::uint8_t {
    None,
    Input,        // the e-stop input was active
    ReadError,    // the e-stop input could not be read
    OutputFault,  // the drive-enable output could not be written
    Requested,    // software asked for a stop (request_stop)
    Startup,      // never reset since construction: the latch starts stopped (fail safe)
    Contact,      // the firmware's contact monitor detected a contact (fw.yaml monitor.action: stop)
};

inline const char* describe(StopCause c) noexcept {
    switch (c) {
        case StopCause::None: return "not stopped";
        case StopCause::Input: return "e-stop input active";
        case StopCause::ReadError: return "e-stop input read failed (counts as a stop)";
        case StopCause::OutputFault: return "drive-enable output write failed";
        case StopCause::Requested: return "stop requested by software";
        case StopCause::Startup: return "e-stop not yet reset since start";
        case StopCause::Contact: return "contact detected by the monitor";
    }
    return "unknown stop cause";
}

// The latch alone: fed with each read of the e-stop input.
class EStopLatch {
public:
    explicit EStopLatch(bool active_low = true) noexcept : active_low_(active_low) {}

    // One read of the input: its status and physical level. Returns whether the latch is stopped.
    bool update(GpioStatus read_status, bool level) noexcept {
        if (read_status != GpioStatus::Ok) {
            ++read_errors_;
            last_read_released_ = false;
            trip(StopCause::ReadError);
        } else {
            const bool active = active_low_ ? !level : level;
            last_read_released_ = !active;
            if (active) trip(StopCause::Input);
        }
        return stopped_;
    }

    void request_stop(StopCause cause = StopCause::Requested) noexcept { trip(cause); }

    // Clears the latch only if the last read succeeded and showed the input released.
    bool reset() noexcept {
        if (!last_read_released_) return false;
        stopped_ = false;
        cause_ = StopCause::None;
        return true;
    }

    bool stopped() const noexcept { return stopped_; }
    StopCause cause() const noexcept { return cause_; }  // first cause since the last reset
    std::uint64_t read_errors() const noexcept { return read_errors_; }
    std::uint64_t stop_events() const noexcept { return stop_events_; }  // transitions into stopped

private:
    void trip(StopCause cause) noexcept {
        if (!stopped_) {
            stopped_ = true;
            cause_ = cause;
            ++stop_events_;
        }
    }

    bool active_low_ = true;
    bool stopped_ = true;           // stopped until a first good read and a reset: fail safe at start
    StopCause cause_ = StopCause::Startup;
    bool last_read_released_ = false;
    std::uint64_t read_errors_ = 0;
    std::uint64_t stop_events_ = 0;
};

struct SafetyIoConfig {
    bool estop_active_low = true;   // e-stop chains are normally closed: the input goes low on a press
    bool enable_active_low = false; // drive-enable level that enables the drives
};

struct SafetyIoCounters {
    std::uint64_t cycles = 0;
    std::uint64_t enable_write_errors = 0;
    std::uint64_t sync_write_errors = 0;
};

class SafetyIo {
public:
    SafetyIo(InputLine& estop, OutputLine& enable, OutputLine& sync, const SafetyIoConfig& config = {}) noexcept
        : estop_(estop), enable_(enable), sync_(sync), config_(config), latch_(config.estop_active_low) {}

    // Once per cycle. Returns whether the drives are enabled after this cycle.
    bool cycle(bool enable_requested) noexcept {
        ++counters_.cycles;
        bool level = false;
        const GpioStatus rs = estop_.read(level);
        const bool stopped = latch_.update(rs, level);
        if (stopped) armed_ = false;
        else if (!enable_requested) armed_ = true;
        const bool enable = enable_requested && !stopped && armed_;
        if (enable_.write(enable != config_.enable_active_low) != GpioStatus::Ok) {
            ++counters_.enable_write_errors;
            latch_.request_stop(StopCause::OutputFault);
            armed_ = false;
            enabled_ = false;
        } else {
            enabled_ = enable;
        }
        sync_level_ = !sync_level_;
        if (sync_.write(sync_level_) != GpioStatus::Ok) ++counters_.sync_write_errors;
        return enabled_;
    }

    // Drops the enable now (outside the cycle, e.g. on shutdown), and latches a stop.
    void stop(StopCause cause = StopCause::Requested) noexcept {
        latch_.request_stop(cause);
        armed_ = false;
        enabled_ = false;
        if (enable_.write(config_.enable_active_low) != GpioStatus::Ok) ++counters_.enable_write_errors;
    }

    // Reads the input now and clears the latch if it is released. The drives stay disabled until the
    // enable request has been seen false once (see the rules above).
    bool reset_estop() noexcept {
        bool level = false;
        const GpioStatus rs = estop_.read(level);
        latch_.update(rs, level);
        return latch_.reset();
    }

    bool enabled() const noexcept { return enabled_; }
    bool stopped() const noexcept { return latch_.stopped(); }
    StopCause stop_cause() const noexcept { return latch_.cause(); }
    const EStopLatch& latch() const noexcept { return latch_; }
    const SafetyIoCounters& counters() const noexcept { return counters_; }
    bool sync_level() const noexcept { return sync_level_; }

private:
    InputLine& estop_;
    OutputLine& enable_;
    OutputLine& sync_;
    SafetyIoConfig config_;
    EStopLatch latch_;
    SafetyIoCounters counters_{};
    bool armed_ = false;
    bool enabled_ = false;
    bool sync_level_ = false;
};

}  // namespace jacobid::hal
