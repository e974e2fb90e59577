// SPDX-License-Identifier: MIT
#include "stream/sequence_tracker.hpp"

#include <algorithm>

namespace jacobid::stream {

Arrival SequenceTracker::push(const HostDatagram& d, SequenceSink& sink) {
    const std::uint64_t s = d.sequence;
    // A restart datagram begins a new numbering; its own duplicates (same number as the epoch's first)
    // must not restart again, so they fall through to the duplicate check below.
    if (started_ && (d.flags & kStreamRestart) != 0 && s != first_) {
        finish(sink);
        sink.restart(s);
        ++counts_.restarts;
        started_ = false;
        epoch_lost_begin_ = lost_.size();
    }
    if (!started_) {
        started_ = true;
        emitted_ = false;
        first_ = next_ = highest_ = s;
    }
    if (s < next_) {
        if (!emitted_) {  // nothing written yet: the stream simply started earlier than we first saw
            next_ = first_ = s;
        } else if (take_from_lost(s)) {
            ++counts_.late;
            late_.push_back(s);
            return Arrival::Late;
        } else {
            ++counts_.duplicated;
            return Arrival::Duplicate;
        }
    }
    if (pending_.count(s) != 0) {
        ++counts_.duplicated;
        return Arrival::Duplicate;
    }
    const bool reordered = s < highest_;
    highest_ = std::max(highest_, s);
    if (reordered) ++counts_.reordered;
    pending_.emplace(s, d);
    // Until the first row is written, the first window of datagrams is held back, so that reordering
    // at the very start moves the start back instead of turning the earliest datagrams into late ones.
    if (emitted_) drain(sink);
    while (pending_.size() > window_) give_up_until(pending_.begin()->first, sink);
    return reordered ? Arrival::Reordered : Arrival::InOrder;
}

void SequenceTracker::finish(SequenceSink& sink) {
    while (!pending_.empty()) give_up_until(pending_.begin()->first, sink);
}

void SequenceTracker::drain(SequenceSink& sink) {
    while (!pending_.empty() && pending_.begin()->first == next_) {
        sink.row(pending_.begin()->second);
        ++counts_.written;
        emitted_ = true;
        pending_.erase(pending_.begin());
        ++next_;
    }
}

void SequenceTracker::give_up_until(std::uint64_t next_present, SequenceSink& sink) {
    if (next_present > next_) {
        const SequenceRange missing{next_, next_present - 1};
        lost_.push_back(missing);
        sink.gap(missing);
        next_ = next_present;
    }
    drain(sink);
}

bool SequenceTracker::take_from_lost(std::uint64_t s) {
    const auto begin = lost_.begin() + static_cast<std::ptrdiff_t>(epoch_lost_begin_);
    auto it = std::upper_bound(begin, lost_.end(), s, [](std::uint64_t v, const SequenceRange& r) { return v < r.first; });
    if (it == begin) return false;
    --it;
    if (s > it->last) return false;
    // Split the range around s (or shrink / remove it).
    if (it->first == it->last) {
        lost_.erase(it);
    } else if (s == it->first) {
        ++it->first;
    } else if (s == it->last) {
        --it->last;
    } else {
        const SequenceRange upper{s + 1, it->last};
        it->last = s - 1;
        lost_.insert(it + 1, upper);
    }
    return true;
}

std::uint64_t SequenceTracker::lost_count() const {
    std::uint64_t n = 0;
    for (const SequenceRange& r : lost_) n += r.count();
    return n;
}

}  // namespace jacobid::stream
