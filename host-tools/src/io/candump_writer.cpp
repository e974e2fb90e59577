// SPDX-License-Identifier: MIT
#include "io/candump_writer.hpp"

#include <fmt/core.h>

#include <cstdio>

#include "core/errors.hpp"
#include "io/candump_joints.hpp"
#include "io/partial_output.hpp"

namespace jacobid::io {

CandumpWriter::CandumpWriter(const std::string& path, std::string interface) : path_(path), interface_(std::move(interface)) {
    file_ = std::fopen(path.c_str(), "w");
    if (!file_) throw InputError(fmt::format("{}: cannot open for writing", path));
}

CandumpWriter::~CandumpWriter() {
    if (!file_) return;
    std::fclose(file_);
    remove_partial_output(path_);
}

void CandumpWriter::close() {
    std::FILE* file = file_;
    file_ = nullptr;
    if (std::fclose(file) != 0) {
        remove_partial_output(path_);
        throw InputError(fmt::format("{}: write failed (disk full?)", path_));
    }
}

hal::CanStatus CandumpWriter::send(const hal::CanFrame& frame) noexcept {
    if (!hal::is_valid_frame(frame)) return hal::CanStatus::InvalidFrame;
    hal::CanFrame stamped = frame;
    stamped.timestamp_ns = now_ns_;
    try {
        const std::string line = format_candump_line(stamped, interface_) + "\n";
        if (std::fwrite(line.data(), 1, line.size(), file_) != line.size()) {
            ++counters_.io_errors;
            return hal::CanStatus::IoError;
        }
    } catch (...) {  // formatting allocates; out of memory is an I/O failure here, not a crash
        ++counters_.io_errors;
        return hal::CanStatus::IoError;
    }
    ++counters_.tx_frames;
    return hal::CanStatus::Ok;
}

}  // namespace jacobid::io
