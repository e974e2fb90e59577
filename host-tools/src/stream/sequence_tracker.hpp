// SPDX-License-Identifier: MIT
#pragma once
// Puts received estimate datagrams back into sequence order and accounts for every sequence number:
// each one is written (once), duplicated, reordered (arrived after a later one but in time to be written
// in order), late (arrived after its place had been given up: not written) or lost (never arrived).
//
// A small reorder buffer (the window) absorbs the reordering that UDP allows; when it overflows, the
// missing numbers before the oldest buffered datagram are given up as a gap. A gap is reported to the sink
// as it happens, so the writer can end a segment there; nothing is ever interpolated over.
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "jacobid/stream/estimate_datagram.hpp"

namespace jacobid::stream {

// The host accepts up to 64 joints per stream (a humanoid's worth); the format itself allows 1487.
constexpr std::size_t kHostMaxJoints = 64;
using HostDatagram = EstimateDatagram<kHostMaxJoints>;

// An inclusive range of sequence numbers.
struct SequenceRange {
    std::uint64_t first = 0;
    std::uint64_t last = 0;
    std::uint64_t count() const { return last - first + 1; }
};

enum class Arrival {
    InOrder,    // buffered or written in order
    Reordered,  // arrived after a higher sequence number, still written in order
    Duplicate,  // this sequence number was already received: dropped
    Late,       // arrived after its gap had been declared: not written (the gap stays)
};

class SequenceSink {
public:
    virtual ~SequenceSink() = default;
    virtual void row(const HostDatagram& d) = 0;
    // The datagrams `missing` will never be written; the next row follows them.
    virtual void gap(const SequenceRange& missing) = 0;
    // The controller restarted its stream (kStreamRestart): what follows is a new recording.
    virtual void restart(std::uint64_t sequence) = 0;
};

struct SequenceCounts {
    std::uint64_t written = 0;
    std::uint64_t duplicated = 0;
    std::uint64_t reordered = 0;
    std::uint64_t late = 0;
    std::uint64_t restarts = 0;
};

class SequenceTracker {
public:
    explicit SequenceTracker(std::size_t reorder_window) : window_(reorder_window) {}

    Arrival push(const HostDatagram& d, SequenceSink& sink);
    // End of recording: writes every buffered datagram, declaring the gaps between them.
    void finish(SequenceSink& sink);

    const SequenceCounts& counts() const { return counts_; }
    // Numbers given up and never received (late arrivals are not in here: see counts().late).
    const std::vector<SequenceRange>& lost() const { return lost_; }
    std::uint64_t lost_count() const;
    // Numbers that arrived too late to be written, in arrival order.
    const std::vector<std::uint64_t>& late() const { return late_; }
    bool started() const { return started_; }
    std::uint64_t first_sequence() const { return first_; }
    std::uint64_t highest_sequence() const { return highest_; }
    std::size_t buffered() const { return pending_.size(); }

private:
    void drain(SequenceSink& sink);
    void give_up_until(std::uint64_t next_present, SequenceSink& sink);
    bool take_from_lost(std::uint64_t sequence);

    std::size_t window_;
    bool started_ = false;
    bool emitted_ = false;  // before the first row, an earlier number moves the start back (not "late")
    std::uint64_t first_ = 0;
    std::uint64_t next_ = 0;     // next sequence number to write
    std::uint64_t highest_ = 0;  // highest received so far
    std::map<std::uint64_t, HostDatagram> pending_;
    std::vector<SequenceRange> lost_;  // sorted and disjoint within an epoch (between restarts)
    std::size_t epoch_lost_begin_ = 0;  // first entry of lost_ in the current epoch
    std::vector<std::uint64_t> late_;
    SequenceCounts counts_;
};

}  // namespace jacobid::stream
