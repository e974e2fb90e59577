// SPDX-License-Identifier: MIT
// SequenceTracker in process: every arrival pattern accounted for exactly, rows in order, gaps reported
// where they happen (the CLI tests cover the same through real sockets; these cover the corner cases).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "stream/recorder.hpp"
#include "stream/sequence_tracker.hpp"

namespace {

namespace st = jacobid::stream;

struct Log : st::SequenceSink {
    std::string events;  // "r5 g6-7 r8 R0 ..." rows, gaps, restarts in the order they were reported
    void row(const st::HostDatagram& d) override { events += "r" + std::to_string(d.sequence) + " "; }
    void gap(const st::SequenceRange& m) override { events += "g" + std::to_string(m.first) + "-" + std::to_string(m.last) + " "; }
    void restart(std::uint64_t s) override { events += "R" + std::to_string(s) + " "; }
};

st::HostDatagram datagram(std::uint64_t seq, std::uint32_t flags = 0) {
    st::HostDatagram d;
    d.sequence = seq;
    d.flags = flags;
    d.joint_count = 1;
    d.sample_period = 1e-3;
    return d;
}

std::string run(st::SequenceTracker& t, const std::vector<std::uint64_t>& arrivals) {
    Log log;
    for (std::uint64_t s : arrivals) t.push(datagram(s), log);
    t.finish(log);
    return log.events;
}

TEST(StreamSequenceTracker, InOrderStreamIsWrittenAsIs) {
    st::SequenceTracker t(4);
    EXPECT_EQ(run(t, {3, 4, 5}), "r3 r4 r5 ");
    EXPECT_EQ(t.counts().written, 3u);
    EXPECT_EQ(t.lost_count(), 0u);
    EXPECT_EQ(t.first_sequence(), 3u);
}

TEST(StreamSequenceTracker, ReorderingWithinTheWindowIsUndone) {
    st::SequenceTracker t(4);
    EXPECT_EQ(run(t, {0, 2, 3, 1, 4}), "r0 r1 r2 r3 r4 ");
    EXPECT_EQ(t.counts().reordered, 1u);
    EXPECT_EQ(t.lost_count(), 0u);
}

TEST(StreamSequenceTracker, EarlierFirstDatagramMovesTheStartBack) {
    st::SequenceTracker t(4);
    EXPECT_EQ(run(t, {1, 0, 2}), "r0 r1 r2 ");  // 1 was buffered: 0 is not late
    EXPECT_EQ(t.counts().reordered, 1u);
    EXPECT_EQ(t.counts().late, 0u);
}

TEST(StreamSequenceTracker, LossIsDeclaredWhenTheWindowOverflowsAndAtTheEnd) {
    st::SequenceTracker t(2);
    Log log;
    for (std::uint64_t s : {0, 1, 3, 4}) t.push(datagram(s), log);
    EXPECT_EQ(log.events, "r0 r1 ");  // 3 and 4 wait for 2
    t.push(datagram(5), log);         // window of 2 overflows: 2 is given up
    EXPECT_EQ(log.events, "r0 r1 g2-2 r3 r4 r5 ");
    for (std::uint64_t s : {8, 9}) t.push(datagram(s), log);
    t.finish(log);
    EXPECT_EQ(log.events, "r0 r1 g2-2 r3 r4 r5 g6-7 r8 r9 ");
    EXPECT_EQ(t.lost_count(), 3u);
    EXPECT_EQ(st::format_ranges(t.lost()), "2, 6-7");
}

TEST(StreamSequenceTracker, LateArrivalLeavesItsGapAndSplitsTheLostRange) {
    st::SequenceTracker t(0);  // no reordering allowed: every hole is given up at once
    EXPECT_EQ(run(t, {0, 5, 3, 3, 6, 0}), "r0 g1-4 r5 r6 ");
    EXPECT_EQ(t.counts().late, 1u);
    EXPECT_EQ(t.counts().duplicated, 2u);  // the second 3 (no longer missing) and the second 0
    EXPECT_EQ(t.lost_count(), 3u);
    EXPECT_EQ(st::format_ranges(t.lost()), "1-2, 4");
}

TEST(StreamSequenceTracker, DuplicatesInTheBufferAndAfterWritingAreCounted) {
    st::SequenceTracker t(8);
    EXPECT_EQ(run(t, {0, 2, 2, 1, 0, 1}), "r0 r1 r2 ");
    EXPECT_EQ(t.counts().duplicated, 3u);
    EXPECT_EQ(t.counts().reordered, 1u);
}

TEST(StreamSequenceTracker, RestartFlagBeginsANewNumbering) {
    st::SequenceTracker t(4);
    Log log;
    for (std::uint64_t s : {100, 101, 103}) t.push(datagram(s), log);
    t.push(datagram(0, st::kStreamRestart), log);
    t.push(datagram(0, st::kStreamRestart), log);  // its duplicate does not restart again
    t.push(datagram(1), log);
    t.finish(log);
    EXPECT_EQ(log.events, "r100 r101 g102-102 r103 R0 r0 r1 ");
    EXPECT_EQ(t.counts().restarts, 1u);
    EXPECT_EQ(t.counts().duplicated, 1u);
}

TEST(StreamSequenceTracker, GapPolicyNames) {
    EXPECT_EQ(st::parse_gap_policy("split"), st::GapPolicy::Split);
    EXPECT_STREQ(st::to_string(st::GapPolicy::Mark), "mark");
    EXPECT_ANY_THROW(st::parse_gap_policy("ignore"));
}

}  // namespace
