// SPDX-License-Identifier: MIT
#pragma once
// libgpiod (v1 C API, Debian 12's 1.6) implementations of the GPIO line interfaces of gpio.hpp.
// The C API is used on purpose: gpiod_line_get_value / gpiod_line_set_value are one ioctl each, while
// the v1 C++ binding builds a std::vector per call. open() and the destructors do the requesting and
// releasing (they may allocate); read() and write() do not.
#include "jacobid/hal/gpio.hpp"

struct gpiod_chip;
struct gpiod_line;

namespace jacobid::hal {

class GpiodChip {
public:
    GpiodChip() noexcept = default;
    ~GpiodChip();
    GpiodChip(const GpiodChip&) = delete;
    GpiodChip& operator=(const GpiodChip&) = delete;

    // name: "gpiochip0", "/dev/gpiochip0", a chip label or a number (gpiod_chip_open_lookup).
    GpioStatus open(const char* name) noexcept;
    void close() noexcept;
    bool is_open() const noexcept { return chip_ != nullptr; }
    gpiod_chip* handle() const noexcept { return chip_; }
    int last_errno() const noexcept { return last_errno_; }

private:
    gpiod_chip* chip_ = nullptr;
    int last_errno_ = 0;
};

class GpiodInputLine final : public InputLine {
public:
    GpiodInputLine() noexcept = default;
    ~GpiodInputLine() override;
    GpiodInputLine(const GpiodInputLine&) = delete;
    GpiodInputLine& operator=(const GpiodInputLine&) = delete;

    // Internal bias (kernel >= 5.5). For an active-low e-stop prefer PullDown (or an external pull-down):
    // a broken wire then reads low, i.e. "stop". A pull-up would make a broken wire read "released".
    enum class Bias { AsIs, PullDown, PullUp };
    GpioStatus open(GpiodChip& chip, unsigned offset, const char* consumer, Bias bias = Bias::AsIs) noexcept;
    void release() noexcept;
    GpioStatus read(bool& level) noexcept override;
    int last_errno() const noexcept { return last_errno_; }

private:
    gpiod_line* line_ = nullptr;
    int last_errno_ = 0;
};

class GpiodOutputLine final : public OutputLine {
public:
    GpiodOutputLine() noexcept = default;
    ~GpiodOutputLine() override;
    GpiodOutputLine(const GpiodOutputLine&) = delete;
    GpiodOutputLine& operator=(const GpiodOutputLine&) = delete;

    GpioStatus open(GpiodChip& chip, unsigned offset, const char* consumer, bool initial_level) noexcept;
    void release() noexcept;
    GpioStatus write(bool level) noexcept override;
    int last_errno() const noexcept { return last_errno_; }

private:
    gpiod_line* line_ = nullptr;
    int last_errno_ = 0;
};

}  // namespace jacobid::hal
