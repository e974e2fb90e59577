// SPDX-License-Identifier: MIT
// FirmwareCycle on the virtual bus with simulated time: alignment of what a datagram says, zero heap
// allocation over many cycles, and fault injection (each fault detected, counted and flagged).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "allocation_counter.hpp"
#include "firmware_test_support.hpp"
#include "monitor_test_support.hpp"
#include "jacobid/firmware/jitter_stats.hpp"
#include "jacobid/firmware/runtime.hpp"
#include "sim/can_player.hpp"

namespace {

using namespace jacobid;
using test::FakeInput;
using test::FakeOutput;

constexpr std::int64_t kPeriodNs = 1'000'000;

struct Row {
    std::uint64_t sequence = 0, sample_index = 0;
    std::int64_t timestamp_ns = 0;
    std::uint32_t stream_flags = 0;
    std::vector<stream::JointEstimate> joints;
};

// Simulator, bus, GPIO and firmware wired together; tick() is one 1 ms cycle.
struct Rig {
    test::TestBus bus;
    test::TestBus::Endpoint* fw = bus.attach();
    test::TestBus::Endpoint* sim = bus.attach();
    test::FaultyTransport faulty{*sim};
    FakeInput estop;
    FakeOutput enable, sync;
    hal::SafetyIo safety{estop, enable, sync};
    test::MemoryPublisher publisher;
    firmware::FirmwareConfig config = test::chain_config();
    std::unique_ptr<firmware::FirmwareCycle> cycle = std::make_unique<firmware::FirmwareCycle>(*fw, publisher, &safety);
    sim::CanPlayer player{faulty, test::profiles_of(config)};
    std::vector<Row> rows;
    std::uint64_t k = 0;  // call index = the sample index the bank will give this sample
    bool keep_rows = true;
    std::function<void(std::uint64_t)> before_step;  // fault hooks at call k

    Rig() {
        EXPECT_EQ(cycle->configure(config), "");
        EXPECT_TRUE(cycle->reset_estop());
        publisher.on_datagram = [this](Span<const std::uint8_t>) {
            if (!keep_rows) return;
            Row r{publisher.last.sequence, publisher.last.sample_index, publisher.last.timestamp_ns, publisher.last.flags, {}};
            r.joints.assign(publisher.last.joints.begin(), publisher.last.joints.begin() + static_cast<long>(publisher.last.joint_count));
            rows.push_back(r);
        };
    }
    static double q_of(std::size_t j, double t) { return 0.8 * std::sin(2.0 * M_PI * 0.7 * t + static_cast<double>(j)); }
    static double tau_of(std::size_t j, double t) { return (j == 0 ? 20.0 : 1.5) * std::cos(2.0 * M_PI * 0.3 * t); }

    void tick() {
        const std::int64_t now = static_cast<std::int64_t>(k) * kPeriodNs + 1'000'000'000;
        const double t = static_cast<double>(k) * 1e-3;
        double q[2], qd[2], tau[2];
        for (std::size_t j = 0; j < 2; ++j) {
            q[j] = q_of(j, t);
            qd[j] = 0.8 * 2.0 * M_PI * 0.7 * std::cos(2.0 * M_PI * 0.7 * t + static_cast<double>(j));
            tau[j] = tau_of(j, t);
        }
        bus.set_time_ns(now);
        if (before_step) before_step(k);
        player.send(q, qd, tau);
        cycle->step(now);
        ++k;
    }
    void run(std::uint64_t n) {
        for (std::uint64_t i = 0; i < n; ++i) tick();
    }
    const Row& row_for_sample(std::uint64_t s) const {
        for (const Row& r : rows) {
            if (r.sample_index == s) return r;
        }
        ADD_FAILURE() << "no row for sample " << s;
        return rows.front();
    }
};

TEST(FirmwareCycle, RowsAreAlignedAndDescribeTheDelayedSample) {
    Rig rig;
    const std::size_t d = rig.cycle->delay_samples();
    EXPECT_EQ(d, 50u);  // central kernels: half the 0.1 s acceleration window
    rig.run(1000);
    ASSERT_EQ(rig.rows.size(), 1000 - d);
    EXPECT_EQ(rig.cycle->counters().datagrams_published, 1000 - d);
    EXPECT_EQ(rig.publisher.last_status, stream::DatagramStatus::Ok);
    for (std::size_t i = 0; i < rig.rows.size(); ++i) {
        const Row& r = rig.rows[i];
        EXPECT_EQ(r.sequence, i);
        EXPECT_EQ(r.sample_index, i);
        // The time stamp is the cycle time of the sample the row describes, not of the newest cycle.
        EXPECT_EQ(r.timestamp_ns, static_cast<std::int64_t>(i) * kPeriodNs + 1'000'000'000);
        EXPECT_EQ(r.stream_flags & stream::kStreamRestart, i == 0 ? stream::kStreamRestart : 0u);
        EXPECT_EQ(r.stream_flags & stream::kStreamEstop, 0u);
    }
    const std::size_t warmup = rig.cycle->warmup_samples();
    for (const Row& r : rig.rows) {
        const bool warming = r.sample_index + d + 1 < warmup;
        for (std::size_t j = 0; j < 2; ++j) {
            EXPECT_EQ(r.joints[j].flags, warming ? stream::kJointWarmup : 0u) << "sample " << r.sample_index;
        }
    }
    // Raw q and tau are the wire values of the sample itself (quantized by the MIT codes); the estimates
    // of a smooth motion agree with the derivatives of the sample's true value.
    const Row& r = rig.row_for_sample(700);
    const double t = 0.7;
    for (std::size_t j = 0; j < 2; ++j) {
        EXPECT_NEAR(r.joints[j].q, Rig::q_of(j, t), 1e-4);
        EXPECT_NEAR(r.joints[j].tau, Rig::tau_of(j, t), j == 0 ? 0.04 : 0.003);
        EXPECT_NEAR(r.joints[j].q_hat, Rig::q_of(j, t), 2e-3);
        const double w = 2.0 * M_PI * 0.7;
        EXPECT_NEAR(r.joints[j].qd_hat, 0.8 * w * std::cos(w * t + static_cast<double>(j)), 0.02);
        EXPECT_NEAR(r.joints[j].qdd_hat, -0.8 * w * w * std::sin(w * t + static_cast<double>(j)), 0.3);
    }
    EXPECT_TRUE(rig.cycle->drive_enabled());
    EXPECT_TRUE(rig.enable.level);
}

// Without and with the contact monitor (fw.yaml `monitor:`, action stop): the Rig's motion is no robot's, so
// the monitor sees contacts all along and its stop path (the e-stop line) runs in the measured stretch too.
TEST(FirmwareZeroAllocation, ManyCyclesOnTheVirtualBusAllocateNothing) {
    for (const bool monitored : {false, true}) {
        SCOPED_TRACE(monitored ? "with the monitor" : "without the monitor");
        Rig rig;
        if (monitored) {
            rig.config = test::monitored_chain_config("alloc", "stop");
            ASSERT_EQ(rig.cycle->configure(rig.config), "");
            ASSERT_TRUE(rig.cycle->reset_estop());
        }
        rig.keep_rows = false;
        rig.publisher.on_datagram = nullptr;
        // Faults in the measured stretch too: their paths must not allocate either.
        rig.faulty.rule = [](hal::CanFrame& f, bool& duplicate) {
            static std::uint64_t n = 0;
            ++n;
            if (n % 97 == 0) return false;       // dropped
            if (n % 89 == 0) duplicate = true;   // duplicated
            if (n % 83 == 0) f.len = 3;          // garbage
            return true;
        };
        rig.run(2000);  // warm-up outside the measurement
        const std::uint64_t contacts_before = rig.cycle->counters().contact_stops;
        const std::uint64_t before = test::allocation_count();
        for (int i = 0; i < 50000; ++i) {
            if (i == 20000) rig.estop.level = false;
            if (i == 20100) rig.bus.inject_error_frame(0x40);
            if (i == 40000) rig.faulty.rule = nullptr;  // clean rows from here: the monitor may detect on them
            if (i == 30000) {
                rig.estop.level = true;
                rig.cycle->reset_estop();  // the operator's reset: a contact may trip the line again
            }
            rig.tick();
        }
        const std::uint64_t after = test::allocation_count();
        EXPECT_EQ(after - before, 0u) << "FirmwareCycle::step (or the virtual bus / CanPlayer::send) allocated";
        EXPECT_EQ(rig.publisher.count, rig.cycle->counters().datagrams_published);
        EXPECT_GT(rig.cycle->counters().duplicate_frames, 0u);
        EXPECT_GT(rig.cycle->counters().decode.rejected_short, 0u);
        EXPECT_EQ(rig.cycle->counters().encode_failures, 0u);
        if (monitored) {
            EXPECT_GT(rig.cycle->counters().contact_stops, contacts_before) << "the contact path did not run in the measured stretch";
            EXPECT_EQ(rig.publisher.last.version, stream::kDatagramVersionMonitor);
        }
    }
    // The counter itself works: a vector allocates.
    const std::uint64_t probe = test::allocation_count();
    std::vector<int> v(10);
    EXPECT_GT(test::allocation_count(), probe);
}

// CANopen SYNC: one zero-length frame with the configured standard id per cycle, seen by the other nodes
// on the bus (the drives), sent after the cycle's read; nothing at all without can.sync_id.
TEST(FirmwareCycle, SendsOneSyncFramePerCycleOnlyWhenConfigured) {
    for (const std::int32_t sync_id : {-1, 0x80}) {
        Rig rig;
        rig.config.sync_id = sync_id;
        ASSERT_EQ(rig.cycle->configure(rig.config), "");
        test::TestBus::Endpoint* drive = rig.bus.attach();  // a listening node
        std::size_t syncs = 0, others = 0;
        for (int c = 0; c < 50; ++c) {
            rig.tick();
            hal::CanFrame f;
            std::size_t this_cycle = 0;
            while (drive->receive(f) == hal::CanStatus::Ok) {
                if (f.id == 0x80u && f.len == 0 && !f.extended() && !f.remote()) ++this_cycle;
                else ++others;  // the simulated drives' replies
            }
            EXPECT_EQ(this_cycle, sync_id < 0 ? 0u : 1u) << "cycle " << c;
            syncs += this_cycle;
        }
        EXPECT_EQ(rig.cycle->counters().sync_sent, syncs);
        EXPECT_EQ(rig.cycle->counters().sync_failures, 0u);
        EXPECT_GT(others, 0u);
        // The firmware does not read its own SYNC as a joint frame.
        EXPECT_EQ(rig.cycle->counters().decode.frames, rig.cycle->counters().decode.decoded);
    }
}

TEST(FirmwareFaults, DroppedFrameIsStaleForThatSampleAndDegradesTheWindow) {
    Rig rig;
    rig.faulty.rule = [&rig](hal::CanFrame& f, bool&) { return !(rig.k == 500 && f.data[0] == 2); };
    rig.run(1000);
    const auto& c = rig.cycle->counters();
    EXPECT_EQ(c.joints[1].stale_samples, 1u);
    EXPECT_EQ(c.joints[0].stale_samples, 0u);
    const Row& r = rig.row_for_sample(500);
    EXPECT_TRUE(r.joints[1].flags & stream::kJointStale);
    EXPECT_FALSE(r.joints[0].flags & stream::kJointStale);
    // Held, not extrapolated: the previous sample's value.
    EXPECT_EQ(r.joints[1].q, rig.row_for_sample(499).joints[1].q);
    EXPECT_FALSE(rig.row_for_sample(499).joints[1].flags & stream::kJointStale);
    EXPECT_FALSE(rig.row_for_sample(501).joints[1].flags & stream::kJointStale);
    // Rows whose windows contain sample 500 are marked, rows far away are not.
    EXPECT_TRUE(rig.row_for_sample(460).joints[1].flags & stream::kJointWindowStale);
    EXPECT_TRUE(rig.row_for_sample(540).joints[1].flags & stream::kJointWindowStale);
    EXPECT_EQ(rig.row_for_sample(400).joints[1].flags, 0u);
    EXPECT_EQ(rig.row_for_sample(600).joints[1].flags, 0u);
    EXPECT_EQ(c.joints[1].window_stale_rows, rig.cycle->warmup_samples());
}

TEST(FirmwareFaults, DuplicatedFramesAreCountedAndConflictingOnesFlagged) {
    Rig rig;
    rig.faulty.rule = [&rig](hal::CanFrame& f, bool& duplicate) {
        if (rig.k == 600 && f.data[0] == 1) duplicate = true;
        return true;
    };
    rig.before_step = [&rig](std::uint64_t k) {
        if (k != 700) return;
        // A second, different reply of motor 1 in the same cycle: two measurements for one sample.
        hal::CanFrame f;
        hal::mit::encode_reply(std::get<hal::mit::JointConfig>(rig.config.joints[0].decoder), 0.123, 0.0, 0.0, f);
        rig.sim->send(f);
    };
    rig.run(1000);
    const auto& c = rig.cycle->counters();
    EXPECT_EQ(c.duplicate_frames, 1u);
    EXPECT_EQ(c.joints[0].duplicate_frames, 1u);
    EXPECT_EQ(c.conflicting_duplicates, 1u);
    EXPECT_EQ(c.joints[0].conflicting_duplicates, 1u);
    // An identical duplicate leaves the measurement exact: no flag (stream format v1 has no duplicate bit).
    EXPECT_EQ(rig.row_for_sample(600).joints[0].flags, 0u);
    EXPECT_TRUE(rig.row_for_sample(700).joints[0].flags & stream::kJointDecodeError);
    EXPECT_EQ(rig.row_for_sample(700).joints[1].flags, 0u);
}

// A transport the test fills frame by frame: it can hand the cycle frames no bus would carry (a standard
// frame with an id beyond 11 bits), as a faulty controller driver might.
class ScriptedTransport final : public hal::CanTransport {
public:
    std::vector<hal::CanFrame> queue;
    hal::CanStatus send(const hal::CanFrame&) noexcept override { return hal::CanStatus::Ok; }
    hal::CanStatus receive(hal::CanFrame& frame) noexcept override {
        if (next_ == queue.size()) {
            queue.clear();
            next_ = 0;
            return hal::CanStatus::Empty;
        }
        frame = queue[next_++];
        return hal::CanStatus::Ok;
    }
    const hal::CanCounters& counters() const noexcept override { return counters_; }
    bool is_open() const noexcept override { return true; }

private:
    std::size_t next_ = 0;
    hal::CanCounters counters_{};
};

// Duplicate detection attributes a frame to the joint whose own decode() took it (no second test that
// could drift, docs/profiles.md): a frame a decoder's test rejects never lands on its joint.
TEST(FirmwareFaults, FramesADecoderRejectsAreNeverAttributedToItsJoint) {
    const firmware::FirmwareConfig config = firmware::parse_firmware_config(
        "can: {interface: virtual}\njoints:\n  - {profile: mit}\n  - {profile: odrive}\nstream: {host: 127.0.0.1, port: 5005}\n", "fw.yaml");
    ScriptedTransport can;
    can.queue.reserve(16);
    test::MemoryPublisher publisher;
    firmware::FirmwareCycle cycle(can, publisher, nullptr);
    ASSERT_EQ(cycle.configure(config), "");
    const hal::ProfileConfig& mit = config.joints[0].decoder;    // motor 1, replies on id 0
    const hal::ProfileConfig& odrive = config.joints[1].decoder; // node 2: 0x049 encoder, 0x054 Iq
    std::array<hal::CanFrame, hal::kMaxTelemetryFrames> out{};
    for (int k = 0; k < 60; ++k) {
        const double q = 0.01 * k;
        for (const hal::ProfileConfig* joint : {&mit, &odrive}) {
            const std::size_t n = hal::encode_telemetry(*joint, q, 0.0, 0.5, out.data());
            can.queue.insert(can.queue.end(), out.begin(), out.begin() + static_cast<long>(n));
        }
        if (k == 20) {
            // Zero-length frames on the MIT reply id, twice: MIT's decode takes them for motor 1 (Short),
            // so they are rejections of joint 0, never decoded frames to compare as duplicates.
            can.queue.push_back(hal::CanFrame{});
            can.queue.push_back(hal::CanFrame{});
        }
        if (k == 30) {
            // Node 2's encoder id with bit 11 set, twice with different payloads: ODrive's decode rejects the
            // id, so no conflicting duplicate is counted against joint 1.
            for (float p : {1.0f, 2.0f}) {
                hal::CanFrame f;
                hal::odrive::pack_encoder_estimates(2, {p, 0.0f}, f);
                f.id |= 0x800u;
                can.queue.push_back(f);
            }
        }
        cycle.step(static_cast<std::int64_t>(k) * kPeriodNs);
    }
    const firmware::CycleCounters& c = cycle.counters();
    EXPECT_EQ(c.decode.rejected_short, 2u);
    EXPECT_EQ(c.decode.rejected_unknown_id, 2u);
    EXPECT_EQ(c.duplicate_frames, 0u);
    EXPECT_EQ(c.conflicting_duplicates, 0u);
    for (std::size_t j = 0; j < 2; ++j) {
        EXPECT_EQ(c.joints[j].duplicate_frames, 0u) << j;
        EXPECT_EQ(c.joints[j].conflicting_duplicates, 0u) << j;
        EXPECT_EQ(c.joints[j].decode_error_samples, 0u) << j;  // each joint's own frames arrived too
    }
    EXPECT_EQ(c.decode.decoded, 60u * 3u);
}

TEST(FirmwareFaults, SilentJointIsStaleForItsWholeSilenceAndHeld) {
    Rig rig;
    rig.faulty.rule = [&rig](hal::CanFrame& f, bool&) { return !(rig.k >= 800 && rig.k < 900 && f.data[0] == 2); };
    rig.run(1200);
    EXPECT_EQ(rig.cycle->counters().joints[1].stale_samples, 100u);
    const double held = rig.row_for_sample(799).joints[1].q;
    for (std::uint64_t s = 800; s < 900; ++s) {
        const Row& r = rig.row_for_sample(s);
        EXPECT_TRUE(r.joints[1].flags & stream::kJointStale) << s;
        EXPECT_EQ(r.joints[1].q, held) << s;
        EXPECT_FALSE(r.joints[0].flags & stream::kJointStale) << s;
    }
    EXPECT_FALSE(rig.row_for_sample(900).joints[1].flags & stream::kJointStale);
    EXPECT_EQ(rig.row_for_sample(1100).joints[1].flags, 0u);
}

TEST(FirmwareFaults, ErrorFramesAreCountedAndTheFrameTheyDestroyedIsStale) {
    Rig rig;
    // A bus error destroys the frame in flight: the controller reports an error frame, the data is lost.
    rig.faulty.rule = [&rig](hal::CanFrame& f, bool&) {
        if (rig.k == 300 && f.data[0] == 1) {
            rig.bus.inject_error_frame(0x04);  // CAN_ERR_PROT
            return false;
        }
        return true;
    };
    rig.run(600);
    const auto& c = rig.cycle->counters();
    EXPECT_EQ(c.can.error_frames, 1u);
    EXPECT_EQ(c.can.last_error_class, 0x04u);
    EXPECT_EQ(c.joints[0].stale_samples, 1u);
    EXPECT_TRUE(rig.row_for_sample(300).joints[0].flags & stream::kJointStale);
    char line[1024];
    EXPECT_NE(std::string(firmware::format_counters(c, 2, line, sizeof line)).find("CAN error frames 1 (last class 0x4)"), std::string::npos)
        << line;
}

TEST(FirmwareFaults, GarbagePayloadsAreRejectedCountedAndFlagged) {
    Rig rig;
    rig.faulty.rule = [&rig](hal::CanFrame& f, bool&) {
        if (rig.k == 400 && f.data[0] == 1) f.len = 3;          // too short for an MIT reply
        if (rig.k == 401 && f.data[0] == 2) f.data[0] = 9;      // no such motor
        if (rig.k == 402 && f.data[0] == 1) f.flags |= hal::kCanRemote;  // a remote frame on the reply id
        return true;
    };
    rig.run(700);
    const auto& c = rig.cycle->counters();
    EXPECT_EQ(c.decode.rejected_short, 1u);
    EXPECT_EQ(c.decode.rejected_unknown_id, 1u);
    EXPECT_EQ(c.decode.rejected_malformed, 1u);
    const Row& r400 = rig.row_for_sample(400);
    EXPECT_TRUE(r400.joints[0].flags & stream::kJointDecodeError);
    EXPECT_TRUE(r400.joints[0].flags & stream::kJointStale);
    // The unknown-id frame cannot be attributed: joint 2 simply did not deliver.
    const Row& r401 = rig.row_for_sample(401);
    EXPECT_TRUE(r401.joints[1].flags & stream::kJointStale);
    EXPECT_FALSE(r401.joints[1].flags & stream::kJointDecodeError);
    EXPECT_TRUE(rig.row_for_sample(402).joints[0].flags & stream::kJointDecodeError);
    EXPECT_EQ(c.joints[0].decode_error_samples, 2u);
    EXPECT_EQ(rig.row_for_sample(600).joints[0].flags, 0u);
}

TEST(FirmwareFaults, EstopDropsEnableInTheSameCycleFlagsTheStreamAndLatches) {
    Rig rig;
    rig.run(300);
    ASSERT_TRUE(rig.enable.level);
    rig.estop.level = false;  // pressed (active low)
    rig.tick();
    EXPECT_FALSE(rig.enable.level) << "drive enable must drop in the cycle that reads the e-stop";
    EXPECT_FALSE(rig.cycle->drive_enabled());
    EXPECT_TRUE(rig.rows.back().stream_flags & stream::kStreamEstop);
    rig.run(50);
    rig.estop.level = true;  // released: the latch holds until a reset
    rig.run(50);
    EXPECT_FALSE(rig.enable.level);
    EXPECT_TRUE(rig.rows.back().stream_flags & stream::kStreamEstop);
    EXPECT_TRUE(rig.cycle->reset_estop());
    rig.tick();  // the enable request is low for one cycle after a reset (no automatic restart on reset)
    EXPECT_FALSE(rig.enable.level);
    rig.tick();
    EXPECT_TRUE(rig.enable.level);
    EXPECT_FALSE(rig.rows.back().stream_flags & stream::kStreamEstop);
    const auto& c = rig.cycle->counters();
    EXPECT_EQ(c.estop_events, 1u);
    EXPECT_EQ(c.estop_rows, 101u);
    // Measurements kept flowing during the stop: nothing stale.
    EXPECT_EQ(c.joints[0].stale_samples + c.joints[1].stale_samples, 0u);
    // A failed read of the e-stop input counts as a stop.
    rig.estop.status = hal::GpioStatus::ReadFailed;
    rig.tick();
    EXPECT_FALSE(rig.enable.level);
    EXPECT_EQ(rig.cycle->counters().estop_events, 2u);
}

TEST(FirmwareFaults, RefusedPublishIsCountedAndTheSequenceShowsTheGap) {
    Rig rig;
    rig.run(100);
    rig.publisher.refuse = true;
    rig.run(3);
    rig.publisher.refuse = false;
    rig.run(1);
    EXPECT_EQ(rig.cycle->counters().publish_failures, 3u);
    EXPECT_EQ(rig.rows.back().sequence, rig.rows[rig.rows.size() - 2].sequence + 4);
}

TEST(FirmwareJitter, HistogramPercentileMinAvgMax) {
    auto s = std::make_unique<firmware::JitterStats>();
    for (int i = 0; i < 990; ++i) s->add(10'000 + i);  // 10.0 .. 10.989 us
    for (int i = 0; i < 10; ++i) s->add(500'000);       // ten 500 us outliers: 1 %
    EXPECT_EQ(s->count(), 1000u);
    EXPECT_NEAR(s->min_us(), 10.0, 1e-9);
    EXPECT_NEAR(s->max_us(), 500.0, 1e-9);
    EXPECT_NEAR(s->avg_us(), (990 * 10.4945 + 10 * 500.0) / 1000.0, 1e-3);
    EXPECT_EQ(s->percentile_us(0.99), 11.0);   // the 990th sample is in the 10 us bin
    EXPECT_EQ(s->percentile_us(0.995), 500.0);
    s->add(20'000'000);  // beyond the histogram: overflow bin, max still exact
    EXPECT_EQ(s->overflow(), 1u);
    EXPECT_NEAR(s->max_us(), 20000.0, 1e-9);
    char line[256];
    EXPECT_NE(std::string(firmware::format_jitter(*s, 2, line, sizeof line)).find("2 overruns"), std::string::npos);
}

}  // namespace
