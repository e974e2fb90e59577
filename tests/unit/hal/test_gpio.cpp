// SPDX-License-Identifier: MIT
// Safety GPIO logic with fake lines (e-stop latch, drive enable, cycle sync), and the libgpiod backend's
// error paths on a machine without GPIO.
#include <gtest/gtest.h>

#include "jacobid/hal/gpio.hpp"
#include "jacobid/hal/gpiod_lines.hpp"

namespace {

using namespace jacobid::hal;

struct FakeInput final : InputLine {
    bool level = true;  // released (active-low e-stop)
    GpioStatus status = GpioStatus::Ok;
    GpioStatus read(bool& out) noexcept override {
        out = level;
        return status;
    }
};
struct FakeOutput final : OutputLine {
    bool level = false;
    int writes = 0;
    GpioStatus status = GpioStatus::Ok;
    GpioStatus write(bool l) noexcept override {
        ++writes;
        if (status == GpioStatus::Ok) level = l;
        return status;
    }
};

struct Rig {
    FakeInput estop;
    FakeOutput enable, sync;
    SafetyIo io{estop, enable, sync};
};

TEST(HalGpio, StartsStoppedUntilReset) {
    Rig r;
    EXPECT_TRUE(r.io.stopped());
    EXPECT_EQ(r.io.stop_cause(), StopCause::Startup);
    EXPECT_FALSE(r.io.cycle(true));
    EXPECT_FALSE(r.enable.level);
    ASSERT_TRUE(r.io.reset_estop());
    EXPECT_FALSE(r.io.cycle(true));  // request still high from before the reset: not re-armed
    EXPECT_FALSE(r.io.cycle(false));
    EXPECT_TRUE(r.io.cycle(true));
    EXPECT_TRUE(r.enable.level);
}

TEST(HalGpio, EStopIsActiveLowAndLatched) {
    Rig r;
    ASSERT_TRUE(r.io.reset_estop());
    r.io.cycle(false);
    ASSERT_TRUE(r.io.cycle(true));
    r.estop.level = false;           // pressed: the line goes low
    EXPECT_FALSE(r.io.cycle(true));  // enable dropped in the same cycle
    EXPECT_FALSE(r.enable.level);
    EXPECT_EQ(r.io.stop_cause(), StopCause::Input);
    r.estop.level = true;            // released again: still latched
    EXPECT_FALSE(r.io.cycle(true));
    EXPECT_TRUE(r.io.stopped());
    r.estop.level = false;
    EXPECT_FALSE(r.io.reset_estop());  // cannot reset while pressed
    r.estop.level = true;
    EXPECT_TRUE(r.io.reset_estop());
    EXPECT_FALSE(r.io.cycle(true));    // needs the request to drop first
    r.io.cycle(false);
    EXPECT_TRUE(r.io.cycle(true));
    EXPECT_EQ(r.io.latch().stop_events(), 1u);  // the press; the startup latch is a state, not an event
}

TEST(HalGpio, ReadErrorCountsAsAStop) {
    Rig r;
    ASSERT_TRUE(r.io.reset_estop());
    r.io.cycle(false);
    ASSERT_TRUE(r.io.cycle(true));
    r.estop.status = GpioStatus::ReadFailed;  // the level the fake reports (released) must be ignored
    EXPECT_FALSE(r.io.cycle(true));
    EXPECT_EQ(r.io.stop_cause(), StopCause::ReadError);
    EXPECT_FALSE(r.io.reset_estop());  // a failing read cannot show "released"
    EXPECT_EQ(r.io.latch().read_errors(), 2u);
    r.estop.status = GpioStatus::Ok;
    EXPECT_TRUE(r.io.reset_estop());
}

TEST(HalGpio, EnableWriteFailureLatchesAStop) {
    Rig r;
    ASSERT_TRUE(r.io.reset_estop());
    r.io.cycle(false);
    r.enable.status = GpioStatus::WriteFailed;
    EXPECT_FALSE(r.io.cycle(true));
    EXPECT_TRUE(r.io.stopped());
    EXPECT_EQ(r.io.stop_cause(), StopCause::OutputFault);
    EXPECT_EQ(r.io.counters().enable_write_errors, 1u);
}

TEST(HalGpio, SyncTogglesOncePerCycleAndActiveLowEnableInverts) {
    FakeInput estop;
    FakeOutput enable, sync;
    SafetyIoConfig cfg;
    cfg.enable_active_low = true;
    SafetyIo io(estop, enable, sync, cfg);
    bool last = sync.level;
    for (int k = 0; k < 10; ++k) {
        io.cycle(false);
        EXPECT_NE(sync.level, last);
        last = sync.level;
        EXPECT_TRUE(enable.level);  // disabled = high for an active-low enable
    }
    EXPECT_EQ(sync.writes, 10);
    ASSERT_TRUE(io.reset_estop());
    io.cycle(false);
    EXPECT_TRUE(io.cycle(true));
    EXPECT_FALSE(enable.level);
    io.stop();
    EXPECT_TRUE(enable.level);
    EXPECT_EQ(io.stop_cause(), StopCause::Requested);
    sync.status = GpioStatus::WriteFailed;
    io.cycle(false);
    EXPECT_EQ(io.counters().sync_write_errors, 1u);
}

TEST(HalGpio, LatchWithActiveHighInput) {
    EStopLatch latch(false);
    EXPECT_TRUE(latch.update(GpioStatus::Ok, false));  // startup latch
    EXPECT_TRUE(latch.reset());
    EXPECT_FALSE(latch.update(GpioStatus::Ok, false));
    EXPECT_TRUE(latch.update(GpioStatus::Ok, true));
    EXPECT_EQ(latch.cause(), StopCause::Input);
}

TEST(HalGpio, LibgpiodReportsAMissingChipAndUnopenedLines) {
    GpiodChip chip;
    EXPECT_EQ(chip.open("jacobid-no-such-gpiochip"), GpioStatus::ChipNotFound);
    EXPECT_FALSE(chip.is_open());
    GpiodInputLine in;
    GpiodOutputLine out;
    EXPECT_EQ(in.open(chip, 0, "jacobid-test"), GpioStatus::NotOpen);
    EXPECT_EQ(out.open(chip, 0, "jacobid-test", false), GpioStatus::NotOpen);
    bool level = true;
    EXPECT_EQ(in.read(level), GpioStatus::NotOpen);
    EXPECT_EQ(out.write(true), GpioStatus::NotOpen);
    // An unopened e-stop line is a read error, so the safety logic stays stopped.
    FakeOutput enable, sync;
    SafetyIo io(in, enable, sync);
    EXPECT_FALSE(io.reset_estop());
    EXPECT_FALSE(io.cycle(true));
    EXPECT_EQ(io.stop_cause(), StopCause::Startup);  // first cause kept
    EXPECT_GE(io.latch().read_errors(), 2u);
}

}  // namespace
