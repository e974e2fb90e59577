// SPDX-License-Identifier: MIT
#pragma once
// The host side of the estimate stream: decodes datagrams, orders them (SequenceTracker) and writes the
// CSV log that `jacobid identify` reads, accounting for everything that did not become a row.
//
// CSV columns: t (s, from the controller's time stamp of the aligned sample, relative to the first row),
// q1..qn and tau1..taun (raw measurements at the aligned sample: what the identifier differentiates
// itself), optionally q1_hat..qn_hat, qd1_hat.., qdd1_hat.. (the controller's estimates), then seq
// (sequence number), stream_flags and flags1..flagsn (the datagram's flag bits), so that every row can be
// traced back to its datagram. See docs/stream-format.md, "Recording".
#include <cstddef>
#include <cstdint>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "stream/sequence_tracker.hpp"

namespace jacobid::stream {

// What to do where the stream has a hole: datagrams lost or late, a row whose measurement is stale or
// undecodable, or a controller restart.
enum class GapPolicy {
    Error,  // write every row received into one file, then fail (exit 2) naming the holes
    Split,  // start a new file at each hole (log.csv, log.2.csv, ...); unmeasured rows are left out
    Mark,   // one file with every row; holes stay visible (time jumps, flags columns), exit 0
};

GapPolicy parse_gap_policy(const std::string& text);
const char* to_string(GapPolicy p);

struct RecorderOptions {
    std::string output;
    GapPolicy policy = GapPolicy::Error;
    bool estimates = false;
    std::size_t reorder_window = 32;
};

struct OutputFile {
    std::string path;
    std::uint64_t rows = 0;
    std::uint64_t first_sequence = 0;
    std::uint64_t last_sequence = 0;
};

class Recorder : private SequenceSink {
public:
    explicit Recorder(RecorderOptions options);
    ~Recorder() override;

    // One received datagram (`full_size` may exceed data.size() when the receive buffer was too small).
    void datagram(const std::vector<std::uint8_t>& data, std::size_t full_size);
    // Flushes the reorder buffer and closes the files. Call once, at the end.
    void finish();

    std::uint64_t received() const { return received_; }
    std::uint64_t malformed() const { return malformed_total_; }
    std::uint64_t rows_written() const { return rows_written_; }
    const SequenceTracker& tracker() const { return tracker_; }
    const std::vector<OutputFile>& files() const { return files_; }

    // Holes that make the recording fail under GapPolicy::Error, one sentence each; empty when complete.
    std::vector<std::string> holes() const;
    // Things worth a warning under every policy (malformed datagrams, e-stop rows, index jumps).
    std::vector<std::string> warnings() const;
    std::string progress_line(double elapsed_seconds) const;
    nlohmann::json summary() const;

private:
    void row(const HostDatagram& d) override;
    void gap(const SequenceRange& missing) override;
    void restart(std::uint64_t sequence) override;
    void open_segment(const HostDatagram& first);
    void close_segment();
    std::string segment_path(std::size_t index) const;

    RecorderOptions options_;
    SequenceTracker tracker_;
    std::unique_ptr<std::ofstream> out_;
    fmt::memory_buffer line_;  // the row being written, reused
    std::vector<OutputFile> files_;

    // Stream description, from the first valid datagram; later datagrams must agree.
    bool described_ = false;
    std::size_t joint_count_ = 0;
    double sample_period_ = 0.0;
    std::uint32_t delay_samples_ = 0;
    std::uint16_t version_ = kDatagramVersion;  // 2: the monitor's tau_ext columns are written too
    bool time_origin_set_ = false;
    std::int64_t time_origin_ns_ = 0;
    std::uint64_t time_origin_index_ = 0;  // controller sample index of the first row

    std::uint64_t received_ = 0;
    std::uint64_t malformed_total_ = 0;
    std::map<std::string, std::uint64_t> malformed_;  // by reason
    std::vector<std::string> malformed_examples_;      // the first few, with their arrival index

    std::uint64_t rows_written_ = 0;
    std::uint64_t rows_stale_ = 0;         // some joint kJointStale
    std::uint64_t rows_decode_error_ = 0;  // some joint kJointDecodeError
    std::uint64_t rows_warmup_ = 0;
    std::uint64_t rows_window_stale_ = 0;
    std::uint64_t rows_estop_ = 0;
    std::uint64_t rows_contact_ = 0;  // stream flag kStreamContact (version 2)
    std::vector<SequenceRange> unmeasured_;  // rows without a fresh measurement of every joint
    std::vector<std::uint64_t> restarts_;    // sequence numbers where the controller restarted
    std::uint64_t sample_index_jumps_ = 0;
    bool have_previous_ = false;
    std::uint64_t previous_sequence_ = 0;
    std::uint64_t previous_sample_index_ = 0;
    bool finished_ = false;
};

// "10-11, 50" (at most `limit` ranges, then "... (N more)").
std::string format_ranges(const std::vector<SequenceRange>& ranges, std::size_t limit = 8);

}  // namespace jacobid::stream
