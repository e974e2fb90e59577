// SPDX-License-Identifier: MIT
#pragma once
// A CanTransport that writes every frame it is given as a `candump -L` line, time-stamped with a clock the
// caller advances (simulated time): the simulator's motor drivers can then produce a capture file exactly
// as candump would have recorded it on a bus.
#include <cstdint>
#include <cstdio>
#include <string>

#include "jacobid/hal/can_transport.hpp"

namespace jacobid::io {

class CandumpWriter final : public hal::CanTransport {
public:
    // Opens `path` for writing; InputError naming it when it cannot.
    CandumpWriter(const std::string& path, std::string interface);
    // Without close() (the run failed half-way) the file is removed: no partial capture looks complete.
    ~CandumpWriter() override;
    CandumpWriter(const CandumpWriter&) = delete;
    CandumpWriter& operator=(const CandumpWriter&) = delete;

    void set_time_ns(std::int64_t t) { now_ns_ = t; }
    // Flushes and closes the capture; InputError naming the file when that fails (a full disk).
    void close();

    hal::CanStatus send(const hal::CanFrame& frame) noexcept override;
    hal::CanStatus receive(hal::CanFrame&) noexcept override { return hal::CanStatus::Empty; }
    const hal::CanCounters& counters() const noexcept override { return counters_; }
    bool is_open() const noexcept override { return file_ != nullptr; }

private:
    std::FILE* file_ = nullptr;
    std::string path_;
    std::string interface_;
    std::int64_t now_ns_ = 0;
    hal::CanCounters counters_{};
};

}  // namespace jacobid::io
