// SPDX-License-Identifier: MIT
#pragma once
// One firmware cycle, without clock, sockets or signals: step(now_ns) drains the CAN transport, decodes
// the joints (JointDecoderSet), applies the safety I/O, runs the streaming differentiator bank and hands
// one encoded estimate datagram (docs/stream-format.md) to a Publisher. The jacobid-fw executable adds the
// clock_nanosleep loop and a UDP publisher; tests drive step() with simulated time and a virtual bus.
//
// Model/Data split: configure() (start-up, may allocate) designs the kernels and copies the joint setup;
// step() allocates nothing and never throws (FirmwareZeroAllocation proves it over many cycles).
//
// What a datagram describes: the bank's estimates are delayed by its common delay d (half the longest
// window for central kernels), so the row of cycle k describes sample k - d. The raw q and tau, the joint
// flags and the time stamp of that sample come from a delay line of d + 1 cycles, so that every field of a
// row refers to the same instant (no mixing of a fresh flag with a delayed estimate).
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "jacobid/differentiator_bank.hpp"
#include "jacobid/firmware/command_log.hpp"
#include "jacobid/firmware/cycle_monitor.hpp"
#include "jacobid/fwconfig/firmware_config.hpp"
#include "jacobid/firmware/trajectory_player.hpp"
#include "jacobid/hal/can_transport.hpp"
#include "jacobid/hal/gpio.hpp"
#include "jacobid/hal/joint_decoder_set.hpp"
#include "jacobid/span.hpp"
#include "jacobid/stream/estimate_datagram.hpp"

namespace jacobid::firmware {

// Where encoded datagrams go (UDP socket, local log, a test's memory). Must not block or allocate.
class Publisher {
public:
    virtual ~Publisher() = default;
    // Returns false when the datagram could not be handed over (counted by the cycle, never retried).
    virtual bool publish(Span<const std::uint8_t> datagram) noexcept = 0;

protected:
    Publisher() = default;
    Publisher(const Publisher&) = default;
    Publisher& operator=(const Publisher&) = default;
};

struct JointCounters {
    std::uint64_t stale_samples = 0;         // samples without a fresh position and torque (held value pushed)
    std::uint64_t decode_error_samples = 0;  // samples whose only frame(s) for the joint were rejected
    std::uint64_t duplicate_frames = 0;      // same CAN id for this joint twice in one cycle, same payload
    std::uint64_t conflicting_duplicates = 0;  // ... with a different payload: the sample is flagged decode-error
    std::uint64_t window_stale_rows = 0;     // published rows whose estimator windows held a bad sample
};

struct CycleCounters {
    std::uint64_t cycles = 0;
    std::uint64_t datagrams_published = 0;
    std::uint64_t publish_failures = 0;  // the publisher refused (e.g. socket buffer full)
    std::uint64_t encode_failures = 0;   // the datagram encoder rejected a row (a bug: values are checked)
    std::uint64_t warmup_rows = 0;       // published rows before the windows were full
    std::uint64_t estop_rows = 0;        // published rows with the e-stop flag
    std::uint64_t estop_events = 0;      // transitions into the stopped state
    std::uint64_t drain_errors = 0;      // transport errors while draining
    std::uint64_t backlog_cycles = 0;    // cycles whose drain filled the frame buffer (frames left queued)
    std::uint64_t duplicate_frames = 0;
    std::uint64_t conflicting_duplicates = 0;
    std::uint64_t sync_sent = 0;         // SYNC frames sent (can.sync_id set)
    std::uint64_t sync_failures = 0;     // SYNC frames the transport refused (e.g. transmit queue full)
    std::uint64_t command_frames = 0;    // playback: command frames sent
    std::uint64_t command_failures = 0;  // playback: command frames the transport refused
    std::uint64_t stop_cycles = 0;       // playback: cycles that sent the stop (hold) command
    std::uint64_t contact_rows = 0;      // monitor: published rows with a confirmed contact
    std::uint64_t contact_events = 0;    // monitor: rows where a contact was confirmed after one without
    std::uint64_t contact_stops = 0;     // monitor: contacts acted on (monitor.action: stop)
    hal::DecodeCounters decode{};        // of the decoder set: frames, decoded, rejected by reason
    hal::CanCounters can{};              // of the transport, copied every cycle (error frames, overflows)
    std::array<JointCounters, kMaxJoints> joints{};
};

class FirmwareCycle {
public:
    using Bank = DifferentiatorBank<double, static_cast<int>(kMaxJoints), kKernelCapacity>;
    using Datagram = stream::EstimateDatagram<kMaxJoints>;

    // `safety` may be null (no GPIO configured). The references must outlive the cycle.
    FirmwareCycle(hal::CanTransport& can, Publisher& publisher, hal::SafetyIo* safety) noexcept;

    // Start-up: validates what the YAML parser cannot (kernel design, alignment, decoder configs) and
    // resets every state and counter. Returns an empty string on success, else a one-line reason.
    std::string configure(const FirmwareConfig& config);

    // One cycle at time now_ns (the cycle's own clock: simulated in tests, CLOCK_MONOTONIC in jacobid-fw).
    void step(std::int64_t now_ns) noexcept;

    // An operator's e-stop reset: clears the latch if the input reads released; the drives come back only
    // after the enable request went low for one cycle (SafetyIo rules). Returns whether the latch cleared.
    bool reset_estop() noexcept;
    // Drops the drive enable now (shutdown path).
    void stop() noexcept;
    // The loop missed a cycle deadline: playback stops in the next step() (a late command is a wrong one).
    void note_missed_deadline() noexcept { deadline_missed_ = true; }
    // Trajectory playback (fw.yaml `trajectory:`): its phase, stop reason and last commands.
    bool playback() const noexcept { return playback_; }
    // Where each playback cycle's commands and measurements go (null: nowhere). Must outlive the cycle.
    void set_command_log(CommandLog* log) noexcept { command_log_ = log; }
    const TrajectoryPlayer& player() const noexcept { return player_; }
    // The contact monitor (fw.yaml `monitor:`): its last row, and the joint of the first contact acted on.
    const CycleMonitor& monitor() const noexcept { return monitor_; }
    int contact_joint() const noexcept { return contact_joint_; }

    bool configured() const noexcept { return configured_; }
    std::size_t joint_count() const noexcept { return joint_count_; }
    std::size_t delay_samples() const noexcept { return bank_.delay_samples(); }
    std::size_t warmup_samples() const noexcept { return bank_.warmup_samples(); }
    const CycleCounters& counters() const noexcept { return counters_; }
    // The last datagram built (also when publishing failed), and its encoded bytes.
    const Datagram& last_datagram() const noexcept { return datagram_; }
    Span<const std::uint8_t> last_encoded() const noexcept { return {encoded_.data(), encoded_size_}; }
    bool drive_enabled() const noexcept { return safety_ != nullptr && safety_->enabled(); }
    bool estop_active() const noexcept { return safety_ != nullptr && safety_->stopped(); }
    const hal::JointDecoderSet<kMaxJoints>& decoders() const noexcept { return decoders_; }

private:
    // A CAN id a joint receives, with the payload of its last frame in the current cycle.
    struct SeenFrame {
        std::uint32_t id = 0;
        std::uint8_t len = 0;
        bool extended = false;
        std::array<std::uint8_t, hal::kCanMaxDataLength> data{};
    };
    struct JointCycle {
        std::array<SeenFrame, 4> seen{};
        std::size_t seen_count = 0;
        bool conflict = false;
    };
    // One delay-line entry: what the row for this sample must say.
    struct SampleRecord {
        std::int64_t time_ns = 0;
        std::array<double, kMaxJoints> q{};
        std::array<std::uint32_t, kMaxJoints> flags{};
    };

    void note_decoded(std::size_t joint, const hal::CanFrame& f) noexcept;
    void update_safety() noexcept;
    void build_row(const Bank::Output& out) noexcept;
    void run_monitor(const Bank::Output& out) noexcept;
    void publish_row() noexcept;
    void run_playback(std::int64_t now_ns) noexcept;
    void send_command(std::size_t joint, const hal::JointCommand& command) noexcept;
    void log_commands(std::int64_t now_ns, const PlayerInput& in, const std::array<hal::JointCommand, kMaxJoints>& sent) noexcept;

    hal::CanTransport& can_;
    Publisher& publisher_;
    hal::SafetyIo* safety_;

    bool configured_ = false;
    std::size_t joint_count_ = 0;
    double sample_period_ = 0.0;
    hal::JointDecoderSet<kMaxJoints> decoders_{};
    Bank bank_{};
    Bank::Output out_{};
    Bank::Vector position_ = Bank::Vector::Zero();
    Bank::Vector torque_ = Bank::Vector::Zero();
    std::array<hal::CanFrame, kMaxFramesPerCycle> frames_{};
    bool send_sync_ = false;
    hal::CanFrame sync_frame_{};  // CANopen SYNC: standard id, no data
    std::array<JointCycle, kMaxJoints> joint_cycle_{};
    std::array<SampleRecord, kKernelCapacity> delay_line_{};
    // Tick (1-based) of the last stale or undecodable sample per joint; 0: none yet.
    std::array<std::uint64_t, kMaxJoints> last_bad_tick_{};
    std::uint64_t ticks_ = 0;
    std::uint64_t sequence_ = 0;
    bool restart_pending_ = true;
    bool enable_request_ = false;  // low for the first cycle after start or a reset: arms the SafetyIo
    bool was_stopped_ = false;
    Datagram datagram_{};
    std::array<std::uint8_t, stream::datagram_size(kMaxJoints, stream::kDatagramVersionMonitor)> encoded_{};
    std::size_t encoded_size_ = 0;
    CycleCounters counters_{};
    // Playback (docs/firmware.md, "Trajectory playback").
    bool playback_ = false;
    TrajectoryPlayer player_{};
    std::array<hal::ProfileConfig, kMaxJoints> profiles_{};
    std::array<hal::CanFrame, hal::kMaxCommandFrames> command_frames_{};
    std::array<hal::JointCommand, kMaxJoints> hold_{};  // the stop: where each joint was when playback stopped
    bool holding_ = false;
    bool deadline_missed_ = false;
    CommandLog* command_log_ = nullptr;
    // Contact monitor (docs/firmware.md, "Contact monitor").
    CycleMonitor monitor_{};
    MonitorAction monitor_action_ = MonitorAction::Stop;
    bool monitor_contact_ = false;  // the previous row had a confirmed contact (for contact_events)
    int contact_joint_ = -1;        // set in the cycle a contact is acted on; read by run_playback
};

}  // namespace jacobid::firmware
