// SPDX-License-Identifier: MIT
#include "stream/recorder.hpp"

#include "io/csv_table.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <iterator>

#include "core/errors.hpp"

namespace jacobid::stream {
namespace {

void append(std::vector<SequenceRange>& ranges, std::uint64_t s) {
    if (!ranges.empty() && ranges.back().last + 1 == s) {
        ranges.back().last = s;
    } else {
        ranges.push_back({s, s});
    }
}

std::uint64_t total(const std::vector<SequenceRange>& ranges) {
    std::uint64_t n = 0;
    for (const auto& r : ranges) n += r.count();
    return n;
}

// Seconds relative to the origin with exact nanoseconds (a double of epoch seconds would round to 0.24 us). The difference of two int64 time stamps can exceed int64 (a corrupt
// or foreign sender's clock), so it is taken as a sign and an unsigned magnitude: no overflow.
// Appended to the row being written, like its other fields.
void append_relative_seconds(fmt::memory_buffer& row, std::int64_t ns, std::int64_t origin_ns) {
    const bool negative = ns < origin_ns;
    const auto a = static_cast<std::uint64_t>(ns), b = static_cast<std::uint64_t>(origin_ns);
    const std::uint64_t magnitude = negative ? b - a : a - b;
    fmt::format_to(std::back_inserter(row), "{}{}.{:09d}", negative ? "-" : "", magnitude / 1000000000u, magnitude % 1000000000u);
}

std::string reason_key(DatagramStatus s) {
    switch (s) {
        case DatagramStatus::Truncated: return "truncated";
        case DatagramStatus::Oversized: return "oversized";
        case DatagramStatus::BadMagic: return "bad_magic";
        case DatagramStatus::UnsupportedVersion: return "unsupported_version";
        case DatagramStatus::NoJoints: return "no_joints";
        case DatagramStatus::TooManyJoints: return "too_many_joints";
        case DatagramStatus::UnknownFlags: return "unknown_flags";
        case DatagramStatus::InvalidSamplePeriod: return "invalid_sample_period";
        case DatagramStatus::NonFiniteMeasurement: return "non_finite_measurement";
        case DatagramStatus::NonFiniteEstimate: return "non_finite_estimate";
        case DatagramStatus::BufferTooSmall:
        case DatagramStatus::Ok: break;
    }
    return "other";
}

}  // namespace

GapPolicy parse_gap_policy(const std::string& text) {
    if (text == "error") return GapPolicy::Error;
    if (text == "split") return GapPolicy::Split;
    if (text == "mark") return GapPolicy::Mark;
    throw InputError(fmt::format("--on-gap '{}': expected error, split or mark", text));
}

const char* to_string(GapPolicy p) {
    switch (p) {
        case GapPolicy::Error: return "error";
        case GapPolicy::Split: return "split";
        case GapPolicy::Mark: return "mark";
    }
    return "?";
}

std::string format_ranges(const std::vector<SequenceRange>& ranges, std::size_t limit) {
    std::string s;
    for (std::size_t i = 0; i < ranges.size() && i < limit; ++i) {
        if (i) s += ", ";
        s += ranges[i].first == ranges[i].last ? fmt::format("{}", ranges[i].first) : fmt::format("{}-{}", ranges[i].first, ranges[i].last);
    }
    if (ranges.size() > limit) s += fmt::format(", ... ({} more ranges)", ranges.size() - limit);
    return s;
}

Recorder::Recorder(RecorderOptions options) : options_(std::move(options)), tracker_(options_.reorder_window) {}

Recorder::~Recorder() = default;

void Recorder::datagram(const std::vector<std::uint8_t>& data, std::size_t full_size) {
    ++received_;
    HostDatagram d;
    DatagramStatus status = full_size > data.size() ? DatagramStatus::Oversized
                                                    : decode(Span<const std::uint8_t>(data.data(), data.size()), d);
    std::string reason, detail;
    if (status != DatagramStatus::Ok) {
        reason = reason_key(status);
        detail = describe(status);
    } else if (described_ && d.joint_count != joint_count_) {
        reason = "inconsistent";
        detail = fmt::format("joint count {} differs from the stream's {}", d.joint_count, joint_count_);
    } else if (described_ && d.version != version_) {
        // The columns follow the version (tau_ext with 2): a file cannot change its columns mid-way.
        reason = "inconsistent";
        detail = fmt::format("version {} differs from the stream's {}", d.version, version_);
    } else if (described_ && d.sample_period != sample_period_) {
        reason = "inconsistent";
        detail = fmt::format("sample period {} s differs from the stream's {} s", d.sample_period, sample_period_);
    } else {
        // Finite but beyond what any measurement is: identify would refuse the log this row went into
        // (io::beyond_log_range), so the row is not written.
        for (std::size_t j = 0; j < d.joint_count && reason.empty(); ++j) {
            const stream::JointEstimate& e = d.joints[j];
            for (double v : {e.q, e.tau, e.q_hat, e.qd_hat, e.qdd_hat, e.tau_ext}) {
                if (io::beyond_log_range(v)) {
                    reason = "out-of-range";
                    detail = fmt::format("joint {}: value {} beyond +-{} (no measurement is)", j + 1, v, io::kMaxLogValue);
                    break;
                }
            }
        }
    }
    if (!reason.empty()) {
        ++malformed_total_;
        ++malformed_[reason];
        if (malformed_examples_.size() < 5) malformed_examples_.push_back(fmt::format("datagram #{} ({} bytes): {}", received_, full_size, detail));
        return;
    }
    if (!described_) {
        described_ = true;
        joint_count_ = d.joint_count;
        sample_period_ = d.sample_period;
        delay_samples_ = d.delay_samples;
        version_ = d.version;
    }
    tracker_.push(d, *this);
}

void Recorder::finish() {
    if (finished_) return;
    finished_ = true;
    tracker_.finish(*this);
    close_segment();
}

std::string Recorder::segment_path(std::size_t index) const {
    if (index == 0) return options_.output;
    const std::filesystem::path p(options_.output);
    return (p.parent_path() / fmt::format("{}.{}{}", p.stem().string(), index + 1, p.extension().string())).string();
}

void Recorder::open_segment(const HostDatagram& first) {
    const std::string path = segment_path(files_.size());
    out_ = std::make_unique<std::ofstream>(path, std::ios::binary | std::ios::trunc);
    if (!*out_) throw InputError(fmt::format("-o {}: cannot write the file", path));
    files_.push_back({path, 0, first.sequence, first.sequence});
    std::string header = "t";
    const std::size_t n = joint_count_;
    for (std::size_t j = 1; j <= n; ++j) header += fmt::format(",q{}", j);
    for (std::size_t j = 1; j <= n; ++j) header += fmt::format(",tau{}", j);
    if (options_.estimates) {
        for (const char* name : {"q", "qd", "qdd"}) {
            for (std::size_t j = 1; j <= n; ++j) header += fmt::format(",{}{}_hat", name, j);
        }
    }
    header += ",seq,stream_flags";
    for (std::size_t j = 1; j <= n; ++j) header += fmt::format(",flags{}", j);
    header += ",t_wake";
    // Version 2 (the controller's contact monitor): its external-torque estimates, after every version-1
    // column so that a reader of version-1 files by position reads the same columns. Named _hat (an
    // estimate), not tau_ext<j>, which is the simulator's logged truth (docs/monitor.md).
    if (version_ == kDatagramVersionMonitor) {
        for (std::size_t j = 1; j <= n; ++j) header += fmt::format(",tau_ext{}_hat", j);
    }
    *out_ << header << '\n';
}

void Recorder::close_segment() {
    if (!out_) return;
    out_->flush();
    if (!*out_) throw InputError(fmt::format("-o {}: writing failed (disk full?)", files_.back().path));
    out_.reset();
}

void Recorder::row(const HostDatagram& d) {
    bool stale = false, decode_error = false, warmup = false, window_stale = false;
    for (std::size_t j = 0; j < d.joint_count; ++j) {
        const std::uint32_t f = d.joints[j].flags;
        stale |= (f & kJointStale) != 0;
        decode_error |= (f & kJointDecodeError) != 0;
        warmup |= (f & kJointWarmup) != 0;
        window_stale |= (f & kJointWindowStale) != 0;
    }
    rows_stale_ += stale;
    rows_decode_error_ += decode_error;
    rows_warmup_ += warmup;
    rows_window_stale_ += window_stale;
    rows_estop_ += (d.flags & kStreamEstop) != 0;
    rows_contact_ += (d.flags & kStreamContact) != 0;
    // Consecutive datagrams should describe consecutive controller samples; a jump means the controller
    // skipped cycles (overrun) or decimates the stream. The time column shows it too; this names it.
    if (have_previous_ && d.sequence == previous_sequence_ + 1 && d.sample_index != previous_sample_index_ + 1) ++sample_index_jumps_;
    have_previous_ = true;
    previous_sequence_ = d.sequence;
    previous_sample_index_ = d.sample_index;

    if (stale || decode_error) {
        append(unmeasured_, d.sequence);
        // A held or missing measurement is not data: under split it ends the segment and is left out.
        if (options_.policy == GapPolicy::Split) {
            close_segment();
            return;
        }
    }
    if (!time_origin_set_) {
        time_origin_set_ = true;
        time_origin_ns_ = d.timestamp_ns;
        time_origin_index_ = d.sample_index;
    }
    if (!out_) open_segment(d);
    // t is the nominal sample time, sample index x sample period: the controller samples once per cycle and
    // the identifier models uniform sampling; the measured wake-up time of the cycle (jitter of tens of us,
    // more than the identifier's 1 % step tolerance at 1 kHz) is kept in t_wake at the end of the row.
    // A skipped controller cycle still shows as a gap in t.
    const auto index = static_cast<double>(static_cast<std::int64_t>(d.sample_index - time_origin_index_));
    // Doubles as fmt's shortest text that reads back to the same double (exact, like %.17g, and about a third of
    // its cost: on a small board at 1 kHz the row's formatting was most of record's CPU). One buffer for every
    // row: no allocation per row.
    line_.clear();
    const auto out = std::back_inserter(line_);
    fmt::format_to(out, "{}", index * d.sample_period);
    const std::size_t n = d.joint_count;
    for (std::size_t j = 0; j < n; ++j) fmt::format_to(out, ",{}", d.joints[j].q);
    for (std::size_t j = 0; j < n; ++j) fmt::format_to(out, ",{}", d.joints[j].tau);
    if (options_.estimates) {
        for (std::size_t j = 0; j < n; ++j) fmt::format_to(out, ",{}", d.joints[j].q_hat);
        for (std::size_t j = 0; j < n; ++j) fmt::format_to(out, ",{}", d.joints[j].qd_hat);
        for (std::size_t j = 0; j < n; ++j) fmt::format_to(out, ",{}", d.joints[j].qdd_hat);
    }
    fmt::format_to(out, ",{},{}", d.sequence, d.flags);
    for (std::size_t j = 0; j < n; ++j) fmt::format_to(out, ",{}", d.joints[j].flags);
    line_.push_back(',');
    append_relative_seconds(line_, d.timestamp_ns, time_origin_ns_);
    if (version_ == kDatagramVersionMonitor) {
        for (std::size_t j = 0; j < n; ++j) fmt::format_to(out, ",{}", d.joints[j].tau_ext);
    }
    line_.push_back('\n');
    out_->write(line_.data(), static_cast<std::streamsize>(line_.size()));
    ++rows_written_;
    ++files_.back().rows;
    files_.back().last_sequence = d.sequence;
}

void Recorder::gap(const SequenceRange&) {
    have_previous_ = false;
    if (options_.policy == GapPolicy::Split) close_segment();
}

void Recorder::restart(std::uint64_t sequence) {
    restarts_.push_back(sequence);
    have_previous_ = false;
    if (options_.policy == GapPolicy::Split) close_segment();
}

std::vector<std::string> Recorder::holes() const {
    std::vector<std::string> h;
    // Late arrivals are holes in the file as well: their place had been given up when they came.
    std::vector<SequenceRange> missing = tracker_.lost();
    for (std::uint64_t s : tracker_.late()) missing.push_back({s, s});
    std::sort(missing.begin(), missing.end(), [](const SequenceRange& a, const SequenceRange& b) { return a.first < b.first; });
    const std::uint64_t lost = tracker_.lost_count(), late = tracker_.counts().late;
    if (lost + late > 0) {
        h.push_back(fmt::format("{} datagram(s) missing (sequence numbers {}; {} lost, {} arrived after the reorder window)",
                                lost + late, format_ranges(missing), lost, late));
    }
    if (!unmeasured_.empty()) {
        h.push_back(fmt::format("{} row(s) without a fresh measurement of every joint, flagged stale or decode-error (sequence numbers {})",
                                total(unmeasured_), format_ranges(unmeasured_)));
    }
    if (!restarts_.empty()) {
        std::vector<SequenceRange> at;
        for (std::uint64_t s : restarts_) at.push_back({s, s});
        h.push_back(fmt::format("the controller restarted its stream {} time(s) (at sequence numbers {})", restarts_.size(), format_ranges(at)));
    }
    return h;
}

std::vector<std::string> Recorder::warnings() const {
    std::vector<std::string> w;
    if (malformed_total_ > 0) {
        std::string reasons;
        for (const auto& [k, v] : malformed_) reasons += fmt::format("{}{} {}", reasons.empty() ? "" : ", ", v, k);
        w.push_back(fmt::format("{} malformed datagram(s) ignored ({}); first: {}", malformed_total_, reasons, malformed_examples_.front()));
    }
    if (tracker_.counts().duplicated > 0) w.push_back(fmt::format("{} duplicated datagram(s) ignored", tracker_.counts().duplicated));
    if (rows_estop_ > 0) w.push_back(fmt::format("{} row(s) recorded while the e-stop was active (stream_flags bit 0)", rows_estop_));
    if (rows_contact_ > 0) w.push_back(fmt::format("{} row(s) with a contact detected by the controller's monitor (stream_flags bit 2)", rows_contact_));
    if (rows_warmup_ > 0) w.push_back(fmt::format("{} row(s) with estimates in warm-up (not valid)", rows_warmup_));
    if (rows_window_stale_ > 0) w.push_back(fmt::format("{} row(s) with a stale sample inside the estimator windows", rows_window_stale_));
    if (sample_index_jumps_ > 0) {
        w.push_back(fmt::format("controller sample index jumped {} time(s) between consecutive datagrams (overruns or decimation)", sample_index_jumps_));
    }
    return w;
}

std::string Recorder::progress_line(double elapsed_seconds) const {
    const auto& c = tracker_.counts();
    return fmt::format("record: {:.0f} s, {} datagrams, {} rows, lost {}, late {}, duplicated {}, reordered {}, malformed {}, buffered {}",
                       elapsed_seconds, received_, rows_written_, tracker_.lost_count(), c.late, c.duplicated, c.reordered, malformed_total_,
                       tracker_.buffered());
}

nlohmann::json Recorder::summary() const {
    using nlohmann::json;
    const auto& c = tracker_.counts();
    json missing = json::array();
    for (const auto& r : tracker_.lost()) missing.push_back({r.first, r.last});
    json unmeasured = json::array();
    for (const auto& r : unmeasured_) unmeasured.push_back({r.first, r.last});
    json files = json::array();
    for (const auto& f : files_) files.push_back({{"path", f.path}, {"rows", f.rows}, {"first_sequence", f.first_sequence}, {"last_sequence", f.last_sequence}});
    json reasons = json::object();
    for (const auto& [k, v] : malformed_) reasons[k] = v;
    json j;
    j["policy"] = to_string(options_.policy);
    j["complete"] = holes().empty();
    j["stream"] = {{"joint_count", joint_count_}, {"sample_period", sample_period_}, {"delay_samples", delay_samples_},
                   {"time_origin_ns", time_origin_ns_}, {"version", version_}};
    j["datagrams"] = {{"received", received_}, {"malformed", malformed_total_}, {"malformed_by_reason", reasons},
                      {"duplicated", c.duplicated}, {"reordered", c.reordered}, {"late", c.late}, {"late_sequences", tracker_.late()},
                      {"lost", tracker_.lost_count()}, {"lost_sequences", missing}, {"restarts", restarts_}};
    if (tracker_.started()) j["datagrams"]["highest_sequence"] = tracker_.highest_sequence();
    j["rows"] = {{"written", rows_written_}, {"stale", rows_stale_}, {"decode_error", rows_decode_error_},
                 {"unmeasured_sequences", unmeasured}, {"estop", rows_estop_}, {"contact", rows_contact_}, {"warmup", rows_warmup_},
                 {"window_stale", rows_window_stale_}, {"sample_index_jumps", sample_index_jumps_}};
    j["files"] = files;
    return j;
}

}  // namespace jacobid::stream
