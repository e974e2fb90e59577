// SPDX-License-Identifier: MIT
// jacobid::hal's libgpiod lines on a real GPIO character device (label gpio): the aarch64 VM's PL061
// (qemu -M virt: gpiochip0, "9030000.pl061", 8 lines; line 3 is wired to the power key, left alone).
// Outputs are read back through the character device; SafetyIo drives real enable and sync lines.
#include <gtest/gtest.h>

#include <gpiod.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "jacobid/hal/gpio.hpp"
#include "jacobid/hal/gpiod_lines.hpp"

namespace {

using namespace jacobid::hal;

const char* chip_name() {
    const char* e = std::getenv("JACOBID_GPIOCHIP");
    return e && *e ? e : "gpiochip0";
}
constexpr unsigned kEnableLine = 0;
constexpr unsigned kSyncLine = 1;
constexpr unsigned kInputLine = 2;

// The level the kernel reports for a line (for an output: what it drives).
int level_of(GpiodChip& chip, unsigned offset) {
    gpiod_line* line = ::gpiod_chip_get_line(chip.handle(), offset);
    return line ? ::gpiod_line_get_value(line) : -1;
}

class GpioChardev : public ::testing::Test {
protected:
    void SetUp() override {
        ASSERT_EQ(chip.open(chip_name()), GpioStatus::Ok)
            << chip_name() << ": " << std::strerror(chip.last_errno()) << " (no GPIO chip: run in the aarch64 VM)";
    }
    GpiodChip chip;
};

// A fake e-stop input: the PL061's input levels are whatever qemu models, so the chain is simulated.
struct FakeInput final : InputLine {
    bool level = true;  // released (active-low chain closed)
    GpioStatus read(bool& l) noexcept override {
        l = level;
        return GpioStatus::Ok;
    }
};

TEST_F(GpioChardev, FindsTheChipByNameAndByLabelAndReportsAMissingOne) {
    EXPECT_GE(::gpiod_chip_num_lines(chip.handle()), 3u);
    const std::string label = ::gpiod_chip_label(chip.handle());
    std::printf("chip %s label %s lines %u\n", ::gpiod_chip_name(chip.handle()), label.c_str(),
                ::gpiod_chip_num_lines(chip.handle()));
    GpiodChip by_label;
    EXPECT_EQ(by_label.open(label.c_str()), GpioStatus::Ok);
    GpiodChip none;
    EXPECT_EQ(none.open("jacobid-no-such-chip"), GpioStatus::ChipNotFound);
    EXPECT_FALSE(none.is_open());
    GpiodOutputLine out;
    EXPECT_EQ(out.open(none, 0, "jacobid-test", false), GpioStatus::NotOpen);
    EXPECT_EQ(out.open(chip, 1000, "jacobid-test", false), GpioStatus::LineNotFound);
    EXPECT_EQ(out.write(true), GpioStatus::NotOpen);
}

TEST_F(GpioChardev, OutputLineIsSetAndReadBackThroughTheCharacterDevice) {
    GpiodOutputLine out;
    ASSERT_EQ(out.open(chip, kEnableLine, "jacobid-test", false), GpioStatus::Ok);
    EXPECT_EQ(level_of(chip, kEnableLine), 0);
    gpiod_line* line = ::gpiod_chip_get_line(chip.handle(), kEnableLine);
    ASSERT_NE(line, nullptr);
    EXPECT_EQ(::gpiod_line_direction(line), GPIOD_LINE_DIRECTION_OUTPUT);
    EXPECT_STREQ(::gpiod_line_consumer(line), "jacobid-test");
    for (int k = 0; k < 10; ++k) {
        const bool level = (k % 2) == 0;
        ASSERT_EQ(out.write(level), GpioStatus::Ok);
        ASSERT_EQ(level_of(chip, kEnableLine), level ? 1 : 0) << k;
    }
    out.release();
    GpiodOutputLine again;  // released lines can be requested again
    EXPECT_EQ(again.open(chip, kEnableLine, "jacobid-test", true), GpioStatus::Ok);
    EXPECT_EQ(level_of(chip, kEnableLine), 1);
}

TEST_F(GpioChardev, ABusyLineIsRefused) {
    GpiodOutputLine first;
    ASSERT_EQ(first.open(chip, kSyncLine, "jacobid-first", false), GpioStatus::Ok);
    GpiodChip other;
    ASSERT_EQ(other.open(chip_name()), GpioStatus::Ok);
    GpiodOutputLine second;
    EXPECT_EQ(second.open(other, kSyncLine, "jacobid-second", true), GpioStatus::RequestFailed);
    EXPECT_EQ(second.last_errno(), EBUSY);
    EXPECT_EQ(level_of(chip, kSyncLine), 0);  // the refused request changed nothing
}

TEST_F(GpioChardev, InputLineReads) {
    GpiodInputLine in;
    ASSERT_EQ(in.open(chip, kInputLine, "jacobid-test"), GpioStatus::Ok);
    bool level = false;
    EXPECT_EQ(in.read(level), GpioStatus::Ok);
    gpiod_line* line = ::gpiod_chip_get_line(chip.handle(), kInputLine);
    EXPECT_EQ(::gpiod_line_direction(line), GPIOD_LINE_DIRECTION_INPUT);
}

TEST_F(GpioChardev, SafetyIoDrivesTheEnableAndSyncLines) {
    GpiodOutputLine enable, sync;
    ASSERT_EQ(enable.open(chip, kEnableLine, "jacobid-enable", false), GpioStatus::Ok);
    ASSERT_EQ(sync.open(chip, kSyncLine, "jacobid-sync", false), GpioStatus::Ok);
    FakeInput estop;
    SafetyIo io(estop, enable, sync);
    EXPECT_FALSE(io.cycle(true));  // latched at start-up
    EXPECT_EQ(level_of(chip, kEnableLine), 0);
    ASSERT_TRUE(io.reset_estop());
    EXPECT_FALSE(io.cycle(true));  // the request must go false once after a stop
    EXPECT_FALSE(io.cycle(false));
    int sync_level = level_of(chip, kSyncLine);
    for (int k = 0; k < 5; ++k) {
        EXPECT_TRUE(io.cycle(true));
        EXPECT_EQ(level_of(chip, kEnableLine), 1) << k;
        const int now = level_of(chip, kSyncLine);
        EXPECT_NE(now, sync_level) << "sync toggles every cycle";
        sync_level = now;
    }
    estop.level = false;  // pressed
    EXPECT_FALSE(io.cycle(true));
    EXPECT_EQ(level_of(chip, kEnableLine), 0);  // dropped in the same cycle
    EXPECT_EQ(io.stop_cause(), StopCause::Input);
    EXPECT_EQ(io.counters().enable_write_errors, 0u);
}

}  // namespace
