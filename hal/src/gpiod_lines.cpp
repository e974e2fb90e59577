// SPDX-License-Identifier: MIT
// libgpiod v1 backend of the GPIO lines. See gpiod_lines.hpp.
#include "jacobid/hal/gpiod_lines.hpp"

#include <gpiod.h>

#include <cerrno>

namespace jacobid::hal {

GpiodChip::~GpiodChip() { close(); }

GpioStatus GpiodChip::open(const char* name) noexcept {
    close();
    errno = 0;
    chip_ = name != nullptr ? ::gpiod_chip_open_lookup(name) : nullptr;
    if (chip_ == nullptr) {
        last_errno_ = errno;
        return GpioStatus::ChipNotFound;
    }
    return GpioStatus::Ok;
}

void GpiodChip::close() noexcept {
    if (chip_ != nullptr) ::gpiod_chip_close(chip_);  // also releases lines still requested
    chip_ = nullptr;
}

namespace {
GpioStatus get_line(GpiodChip& chip, unsigned offset, gpiod_line*& line, int& err) noexcept {
    if (!chip.is_open()) return GpioStatus::NotOpen;
    line = ::gpiod_chip_get_line(chip.handle(), offset);
    if (line == nullptr) {
        err = errno;
        return GpioStatus::LineNotFound;
    }
    return GpioStatus::Ok;
}
}  // namespace

GpiodInputLine::~GpiodInputLine() { release(); }

GpioStatus GpiodInputLine::open(GpiodChip& chip, unsigned offset, const char* consumer, Bias bias) noexcept {
    release();
    gpiod_line* line = nullptr;
    if (const GpioStatus s = get_line(chip, offset, line, last_errno_); s != GpioStatus::Ok) return s;
    int flags = 0;
    if (bias == Bias::PullDown) flags = GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN;
    if (bias == Bias::PullUp) flags = GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
    if (::gpiod_line_request_input_flags(line, consumer, flags) != 0) {
        last_errno_ = errno;
        return GpioStatus::RequestFailed;
    }
    line_ = line;
    return GpioStatus::Ok;
}

void GpiodInputLine::release() noexcept {
    if (line_ != nullptr) ::gpiod_line_release(line_);
    line_ = nullptr;
}

GpioStatus GpiodInputLine::read(bool& level) noexcept {
    if (line_ == nullptr) return GpioStatus::NotOpen;
    const int v = ::gpiod_line_get_value(line_);
    if (v < 0) {
        last_errno_ = errno;
        return GpioStatus::ReadFailed;
    }
    level = v != 0;
    return GpioStatus::Ok;
}

GpiodOutputLine::~GpiodOutputLine() { release(); }

GpioStatus GpiodOutputLine::open(GpiodChip& chip, unsigned offset, const char* consumer, bool initial_level) noexcept {
    release();
    gpiod_line* line = nullptr;
    if (const GpioStatus s = get_line(chip, offset, line, last_errno_); s != GpioStatus::Ok) return s;
    if (::gpiod_line_request_output(line, consumer, initial_level ? 1 : 0) != 0) {
        last_errno_ = errno;
        return GpioStatus::RequestFailed;
    }
    line_ = line;
    return GpioStatus::Ok;
}

void GpiodOutputLine::release() noexcept {
    if (line_ != nullptr) ::gpiod_line_release(line_);
    line_ = nullptr;
}

GpioStatus GpiodOutputLine::write(bool level) noexcept {
    if (line_ == nullptr) return GpioStatus::NotOpen;
    if (::gpiod_line_set_value(line_, level ? 1 : 0) != 0) {
        last_errno_ = errno;
        return GpioStatus::WriteFailed;
    }
    return GpioStatus::Ok;
}

}  // namespace jacobid::hal
