// SPDX-License-Identifier: MIT
#pragma once
// The one place jacobid reads an input file (logs, robot descriptions, URDFs, effects, truth files, candump
// captures, firmware configs). Only a regular file of bounded size is read: a device (/dev/zero), a FIFO or
// a directory would otherwise be read forever or look like an "empty file", and a file of many gigabytes
// would exhaust the memory before any parser could refuse it. The error is thrown as `Error` (the
// firmware's ConfigError, the host tools' InputError), one line naming the file. Header-only, shared by
// firmware/ and host-tools/ like yaml_section.hpp.
#include <fmt/core.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace jacobid::yaml {

// For a file read whole: far above any description or capture, and below what would make the in-memory
// parse the machine's problem.
constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{2} << 30;
// For a log streamed block by block (the CSV reader, which holds only the columns a command keeps and
// checks those against the machine's memory itself): ten hours of 1 kHz 6-axis data as `jacobid simulate`
// writes it are 14 GB; 256 GB is some 180 such hours.
constexpr std::uintmax_t kMaxStreamedInputFileBytes = std::uintmax_t{256} << 30;

// Checks that `path` is a regular file within the bound and returns its size; `what` says what it was meant
// to be ("robot description", "file", ...). For readers that stream the file instead of reading it whole,
// with kMaxStreamedInputFileBytes as `max_bytes`.
template <typename Error>
std::uintmax_t checked_input_file_size(const std::string& path, const std::string& what, std::uintmax_t max_bytes = kMaxInputFileBytes) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (ec || !fs::exists(status)) throw Error(fmt::format("{}: cannot open {}", path, what));
    if (fs::is_directory(status)) throw Error(fmt::format("{}: cannot read {}: it is a directory, not a file", path, what));
    if (!fs::is_regular_file(status)) {
        throw Error(fmt::format("{}: cannot read {}: not a regular file (a device, FIFO or socket)", path, what));
    }
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) throw Error(fmt::format("{}: cannot open {}: {}", path, what, ec.message()));
    if (size > max_bytes) {
        throw Error(fmt::format("{}: cannot read {}: {} MB is more than the {} MB an input file may have", path, what, size >> 20,
                                max_bytes >> 20));
    }
    return size;
}

// The whole file at `path`; `what` says what it was meant to be ("robot description", "file", ...).
template <typename Error>
std::string read_input_file(const std::string& path, const std::string& what) {
    const std::uintmax_t size = checked_input_file_size<Error>(path, what);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(fmt::format("{}: cannot open {}", path, what));
    // Read straight into a string of the file's size (a stringstream grew by doubling and copied the text
    // once more at the end: seconds and three times the memory on a 1 GB log); a file that grows while it
    // is read is taken up to the bound, one that shrinks as far as it goes.
    std::string text(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), static_cast<std::streamsize>(size));
    if (in.bad()) throw Error(fmt::format("{}: read error in {}", path, what));
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (in && in.peek() != std::ifstream::traits_type::eof()) {
        std::ostringstream rest;
        rest << in.rdbuf();
        text += rest.str();
        if (text.size() > kMaxInputFileBytes) {
            throw Error(fmt::format("{}: cannot read {}: more than the {} MB an input file may have", path, what, kMaxInputFileBytes >> 20));
        }
    }
    return text;
}

}  // namespace jacobid::yaml
