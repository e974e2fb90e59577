// SPDX-License-Identifier: MIT
#include "jacobid/firmware/firmware_cycle.hpp"

#include <algorithm>
#include <cstring>
#include <variant>

namespace jacobid::firmware {

FirmwareCycle::FirmwareCycle(hal::CanTransport& can, Publisher& publisher, hal::SafetyIo* safety) noexcept
    : can_(can), publisher_(publisher), safety_(safety) {}

std::string FirmwareCycle::configure(const FirmwareConfig& config) {
    configured_ = false;
    if (config.joints.empty()) return "no joints configured";
    if (config.joints.size() > kMaxJoints) return "more than " + std::to_string(kMaxJoints) + " joints (kMaxJoints)";
    if (!(config.rate > 0.0)) return "rate must be > 0 Hz";
    joint_count_ = config.joints.size();
    sample_period_ = config.sample_period();
    std::array<hal::ProfileConfig, kMaxJoints> profiles{};
    for (std::size_t j = 0; j < joint_count_; ++j) profiles[j] = config.joints[j].decoder;
    const hal::DecoderSetConfigResult d =
        decoders_.configure(Span<const hal::ProfileConfig>(profiles.data(), joint_count_), config.max_age);
    if (d.status != hal::ConfigStatus::Ok) {
        return "joints[" + std::to_string(d.joint) + "]: " + hal::describe(d.status);
    }
    // Padding joints (joint_count_ .. kMaxJoints) get the same kernels and constant zero input: the bank's
    // joint count is a compile-time size.
    std::array<JointFilterConfig, kMaxJoints> filters{};
    for (auto& f : filters) {
        for (int c = 0; c < kChannelCount; ++c) f.params[static_cast<std::size_t>(c)] = kernel_params(config.estimator, sample_period_, c);
    }
    const BankConfigResult b = bank_.configure(filters);
    if (b.status != BankStatus::Ok) {
        static constexpr const char* kChannel[] = {"position_window", "velocity_window", "acceleration_window"};
        std::string why = describe(b.status);
        if (b.status == BankStatus::InvalidKernel) why += std::string(": ") + describe(b.kernel_status);
        return std::string("estimator.") + kChannel[b.channel] + ": " + why;
    }
    if (bank_.delay_samples() + 1 > delay_line_.size()) return "estimator windows too long for the delay line";
    profiles_ = profiles;
    playback_ = config.playback;
    holding_ = false;
    deadline_missed_ = false;
    if (playback_) {
        // The player's reasons name the table (file:line) themselves.
        if (std::string why = player_.configure(config.trajectory, joint_count_, sample_period_); !why.empty()) return why;
    }
    monitor_.disable();
    monitor_action_ = config.monitor.action;
    monitor_contact_ = false;
    contact_joint_ = -1;
    if (config.monitor.enabled) {
        if (std::string why = monitor_.configure(config.monitor.model, joint_count_, sample_period_); !why.empty()) return why;
    }
    if (config.sync_id > static_cast<std::int32_t>(hal::kCanStandardIdMask)) return "can.sync_id must be a standard (11-bit) id";
    send_sync_ = config.sync_id >= 0;
    sync_frame_ = hal::CanFrame{};
    sync_frame_.id = send_sync_ ? static_cast<std::uint32_t>(config.sync_id) : 0u;
    position_.setZero();
    torque_.setZero();
    last_bad_tick_.fill(0);
    ticks_ = 0;
    sequence_ = 0;
    restart_pending_ = true;
    enable_request_ = false;
    was_stopped_ = safety_ != nullptr && safety_->stopped();
    counters_ = CycleCounters{};
    datagram_ = Datagram{};
    datagram_.joint_count = joint_count_;
    // Version 2 only when the monitor streams: without it the stream stays what version-1 receivers read.
    datagram_.version = config.monitor.enabled && config.monitor.stream ? stream::kDatagramVersionMonitor : stream::kDatagramVersion;
    datagram_.sample_period = sample_period_;
    datagram_.delay_samples = static_cast<std::uint32_t>(bank_.delay_samples());
    encoded_size_ = 0;
    configured_ = true;
    return {};
}

// Frames of one CAN id twice in a cycle for the same joint: a retransmission or a bus-level duplicate.
// The joint is the one whose decoder took the frame (JointDecoderSet::route): no second "is it mine"
// test that could drift from the decoders' (docs/profiles.md).
// An identical payload changes nothing (counted only); a different one means two measurements claim one
// sample, so the sample is flagged as a decode error rather than silently taking the later one.
void FirmwareCycle::note_decoded(std::size_t joint, const hal::CanFrame& f) noexcept {
    JointCycle& jc = joint_cycle_[joint];
    JointCounters& c = counters_.joints[joint];
    const std::size_t len = std::min<std::size_t>(f.len, hal::kCanMaxDataLength);
    for (std::size_t i = 0; i < jc.seen_count; ++i) {
        SeenFrame& s = jc.seen[i];
        if (s.id != f.id || s.extended != f.extended()) continue;
        if (s.len == f.len && std::memcmp(s.data.data(), f.data.data(), len) == 0) {
            ++c.duplicate_frames;
            ++counters_.duplicate_frames;
        } else {
            ++c.conflicting_duplicates;
            ++counters_.conflicting_duplicates;
            jc.conflict = true;
        }
        return;
    }
    if (jc.seen_count == jc.seen.size()) return;
    SeenFrame& s = jc.seen[jc.seen_count++];
    s.id = f.id;
    s.extended = f.extended();
    s.len = f.len;
    std::memcpy(s.data.data(), f.data.data(), len);
}

void FirmwareCycle::update_safety() noexcept {
    if (safety_ == nullptr) return;
    safety_->cycle(enable_request_);
    // The drives are wanted on: the request rises after one low cycle (SafetyIo re-arms on a low request).
    enable_request_ = true;
    const bool stopped = safety_->stopped();
    if (stopped && !was_stopped_) ++counters_.estop_events;
    was_stopped_ = stopped;
}

bool FirmwareCycle::reset_estop() noexcept {
    if (safety_ == nullptr) return false;
    const bool cleared = safety_->reset_estop();
    if (cleared) {
        enable_request_ = false;
        was_stopped_ = false;
        contact_joint_ = -1;  // the operator's reset also acknowledges a contact's stop
    }
    return cleared;
}

void FirmwareCycle::stop() noexcept {
    if (safety_ != nullptr) safety_->stop();
}

void FirmwareCycle::step(std::int64_t now_ns) noexcept {
    if (!configured_) return;
    ++counters_.cycles;
    // Safety first: an e-stop drops the enable in this cycle whatever happens on the bus.
    update_safety();

    decoders_.begin_cycle();
    for (std::size_t j = 0; j < joint_count_; ++j) {
        joint_cycle_[j].seen_count = 0;
        joint_cycle_[j].conflict = false;
    }
    const hal::DrainResult drained = can_.drain(Span<hal::CanFrame>(frames_.data(), frames_.size()));
    if (drained.status != hal::CanStatus::Ok) ++counters_.drain_errors;
    if (drained.count == frames_.size()) ++counters_.backlog_cycles;
    for (std::size_t i = 0; i < drained.count; ++i) {
        const hal::CanFrame& f = frames_[i];
        const hal::RouteResult routed = decoders_.route(f);
        if (routed.status == hal::DecodeStatus::Ok) note_decoded(routed.joint, f);
    }
    // SYNC right after the read: the drives' answers have the rest of this period to arrive and are
    // all read at the start of the next cycle, one sample per joint per cycle.
    if (send_sync_) {
        if (can_.send(sync_frame_) == hal::CanStatus::Ok) ++counters_.sync_sent;
        else ++counters_.sync_failures;
    }
    ++ticks_;
    SampleRecord& rec = delay_line_[ticks_ % delay_line_.size()];
    rec.time_ns = now_ns;
    for (std::size_t j = 0; j < joint_count_; ++j) {
        const hal::JointState& s = decoders_.state(j);
        std::uint32_t flags = 0;
        // A joint that did not deliver this cycle keeps its last value in the bank (a hold, never an
        // extrapolation) and the sample is flagged; a joint never heard from pushes 0.
        if (s.stale) flags |= stream::kJointStale;
        if ((s.decode_error && !s.fresh()) || joint_cycle_[j].conflict) flags |= stream::kJointDecodeError;
        JointCounters& c = counters_.joints[j];
        if (flags & stream::kJointStale) ++c.stale_samples;
        if (flags & stream::kJointDecodeError) ++c.decode_error_samples;
        if (flags != 0) last_bad_tick_[j] = ticks_;
        position_[static_cast<Eigen::Index>(j)] = s.position;
        torque_[static_cast<Eigen::Index>(j)] = s.torque;
        rec.q[j] = s.position;
        rec.flags[j] = flags;
    }
    bank_.step(position_, torque_, out_);
    // The first row is the first cycle whose aligned sample exists (tick d + 1). The monitor runs on it
    // before the playback, so that a contact's stop is this cycle's command.
    const bool aligned = ticks_ > bank_.delay_samples();
    if (aligned) {
        build_row(out_);
        run_monitor(out_);
    }
    if (playback_) run_playback(now_ns);
    counters_.decode = decoders_.counters();
    counters_.can = can_.counters();
    if (aligned) publish_row();
}

// The external torque of the row's instant, its contact flags and, on a confirmed contact with
// monitor.action stop, the action: the drive enable dropped now (the e-stop line) and the playback's hold
// sent by run_playback in this same cycle.
void FirmwareCycle::run_monitor(const Bank::Output& out) noexcept {
    if (!monitor_.enabled()) return;
    Datagram& d = datagram_;
    bool trusted = true;
    for (std::size_t j = 0; j < joint_count_; ++j) trusted = trusted && d.joints[j].flags == 0;
    const MonitorRow& row = monitor_.step(out.position, out.velocity, out.torque, out.valid, trusted);
    const bool streamed = d.version == stream::kDatagramVersionMonitor;
    for (std::size_t j = 0; j < joint_count_; ++j) {
        d.joints[j].tau_ext = row.external[j];
        if (streamed && (row.over >> j & 1u) != 0) d.joints[j].flags |= stream::kJointContact;
    }
    if (row.contact) {
        if (streamed) d.flags |= stream::kStreamContact;
        ++counters_.contact_rows;
        if (!monitor_contact_) ++counters_.contact_events;
    }
    monitor_contact_ = row.contact;
    if (!row.contact || monitor_action_ != MonitorAction::Stop) return;
    ++counters_.contact_stops;
    if (contact_joint_ < 0) {
        for (std::size_t j = 0; j < joint_count_ && contact_joint_ < 0; ++j) {
            if ((row.over >> j & 1u) != 0) contact_joint_ = static_cast<int>(j);
        }
    }
    if (safety_ != nullptr && !safety_->stopped()) safety_->stop(hal::StopCause::Contact);
    if (safety_ != nullptr) d.flags |= stream::kStreamEstop;
}

void FirmwareCycle::send_command(std::size_t joint, const hal::JointCommand& command) noexcept {
    const std::size_t n = hal::encode_command(profiles_[joint], command, command_frames_.data());
    for (std::size_t i = 0; i < n; ++i) {
        if (can_.send(command_frames_[i]) == hal::CanStatus::Ok) ++counters_.command_frames;
        else ++counters_.command_failures;
    }
}

// Playback starts once every joint has been measured with the drives enabled (the ramp begins where the
// robot stands); from then on every cycle sends each joint's command, or, once stopped, a hold where the
// joint was at the stop (position mode: that position at rest, the drive's own gains; torque mode: zero
// torque). The e-stop line drops the enable in hardware whatever is sent.
void FirmwareCycle::log_commands(std::int64_t now_ns, const PlayerInput& in, const std::array<hal::JointCommand, kMaxJoints>& sent) noexcept {
    if (command_log_ == nullptr) return;
    CommandRecord r;
    r.time_ns = now_ns;
    r.phase = player_.phase();
    r.reason = player_.stop_reason();
    r.row = player_.row();
    r.joints = joint_count_;
    for (std::size_t j = 0; j < joint_count_; ++j) {
        r.measured[j] = in.q[j];
        r.position[j] = sent[j].position;
        r.velocity[j] = sent[j].velocity;
        r.torque[j] = sent[j].torque;
    }
    command_log_->record(r);
}

void FirmwareCycle::run_playback(std::int64_t now_ns) noexcept {
    const bool enabled = safety_ == nullptr || safety_->enabled();
    if (player_.phase() == PlaybackPhase::Idle) {
        // An overrun while nothing is commanded yet (start-up, waiting for every joint's first sample) puts
        // nothing at risk: the loop counts it, the playback that starts later must not inherit it.
        deadline_missed_ = false;
        if (!enabled) return;
        for (std::size_t j = 0; j < joint_count_; ++j) {
            const hal::JointState& s = decoders_.state(j);
            if (s.stale || !s.position_fresh) return;
        }
        player_.start();
    }
    PlayerInput in;
    for (std::size_t j = 0; j < joint_count_; ++j) {
        const hal::JointState& s = decoders_.state(j);
        in.q[j] = s.position;
        in.fresh[j] = s.position_fresh && !s.stale;
        in.fault[j] = s.device_error != 0;
    }
    in.estop = safety_ != nullptr && safety_->stopped();
    in.contact_joint = contact_joint_;
    in.deadline_missed = deadline_missed_;
    deadline_missed_ = false;
    player_.step(in);
    if (player_.stop_drives()) {
        if (!holding_) {
            holding_ = true;
            for (std::size_t j = 0; j < joint_count_; ++j) {
                const PlaybackConfig& c = player_.config();
                hold_[j] = hal::JointCommand{c.mode, in.q[j], 0.0, 0.0, c.kp[j], c.kd[j]};
            }
        }
        ++counters_.stop_cycles;
        for (std::size_t j = 0; j < joint_count_; ++j) send_command(j, hold_[j]);
        log_commands(now_ns, in, hold_);
        return;
    }
    // Active, or finished: the last row is held.
    for (std::size_t j = 0; j < joint_count_; ++j) send_command(j, player_.commands()[j]);
    log_commands(now_ns, in, player_.commands());
}

void FirmwareCycle::build_row(const Bank::Output& out) noexcept {
    const std::uint64_t aligned_tick = ticks_ - bank_.delay_samples();
    const SampleRecord& rec = delay_line_[aligned_tick % delay_line_.size()];
    // Every sample the bank's windows read is among the newest warmup_samples() ticks.
    const std::uint64_t window = bank_.warmup_samples();
    Datagram& d = datagram_;
    d.sequence = sequence_;
    d.sample_index = out.sample_index;
    d.timestamp_ns = rec.time_ns;
    d.flags = 0;
    if (restart_pending_) d.flags |= stream::kStreamRestart;
    if (safety_ != nullptr && safety_->stopped()) d.flags |= stream::kStreamEstop;
    for (std::size_t j = 0; j < joint_count_; ++j) {
        const auto i = static_cast<Eigen::Index>(j);
        stream::JointEstimate& e = d.joints[j];
        e.q = rec.q[j];
        e.q_hat = out.position[i];
        e.qd_hat = out.velocity[i];
        e.qdd_hat = out.acceleration[i];
        e.tau = out.torque[i];
        e.flags = rec.flags[j];
        if (!out.valid) e.flags |= stream::kJointWarmup;
        if (last_bad_tick_[j] != 0 && last_bad_tick_[j] + window > ticks_) {
            e.flags |= stream::kJointWindowStale;
            ++counters_.joints[j].window_stale_rows;
        }
        e.tau_ext = 0.0;
    }
    if (!out.valid) ++counters_.warmup_rows;
}

void FirmwareCycle::publish_row() noexcept {
    Datagram& d = datagram_;
    if (d.flags & stream::kStreamEstop) ++counters_.estop_rows;
    const stream::DatagramStatus st = stream::encode(d, Span<std::uint8_t>(encoded_.data(), encoded_.size()), encoded_size_);
    ++sequence_;
    if (st != stream::DatagramStatus::Ok) {
        ++counters_.encode_failures;
        return;
    }
    restart_pending_ = false;
    if (publisher_.publish(Span<const std::uint8_t>(encoded_.data(), encoded_size_))) ++counters_.datagrams_published;
    else ++counters_.publish_failures;
}

}  // namespace jacobid::firmware
