// SPDX-License-Identifier: MIT
#include "options/output_file.hpp"

#include <fmt/core.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/errors.hpp"
#include "core/same_file.hpp"

namespace jacobid::options {

namespace fs = std::filesystem;

namespace {

bool given(const NamedPath& p) { return !p.path.empty() && p.path != "-"; }

// "F" when both options named F, else "F (the file X)": a link or another spelling of X.
std::string naming(const NamedPath& out, const NamedPath& in) {
    return out.path == in.path ? out.path : fmt::format("{} (the file {})", out.path, in.path);
}

void check_writable(const NamedPath& out) {
    std::error_code ec;
    const fs::path parent = fs::absolute(out.path, ec).parent_path();
    if (!fs::is_directory(parent, ec)) throw InputError(fmt::format("{} {}: directory '{}' does not exist", out.option, out.path, parent.string()));
    if (fs::is_directory(out.path, ec)) throw InputError(fmt::format("{} {}: is a directory, expected a file name", out.option, out.path));
    const bool existed = fs::exists(out.path, ec);
    // Append mode: an existing file is left as it is until the command writes its result.
    std::FILE* f = std::fopen(out.path.c_str(), "ab");
    if (!f) throw InputError(fmt::format("{} {}: cannot open for writing: {}", out.option, out.path, std::strerror(errno)));
    std::fclose(f);
    if (!existed) fs::remove(out.path, ec);
}

}  // namespace

void check_outputs(std::initializer_list<NamedPath> outputs, std::initializer_list<NamedPath> inputs) {
    check_outputs(outputs, std::vector<NamedPath>(inputs));
}

void check_outputs(std::initializer_list<NamedPath> outputs, const std::vector<NamedPath>& inputs) {
    check_outputs(std::vector<NamedPath>(outputs), inputs);
}

void check_outputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
    for (auto out = outputs.begin(); out != outputs.end(); ++out) {
        if (!given(*out)) continue;
        for (const NamedPath& in : inputs) {
            if (given(in) && same_file(out->path, in.path)) {
                throw InputError(fmt::format("{} {}: is the input given to {}; write the result to another file", out->option, naming(*out, in), in.option));
            }
        }
        for (auto other = outputs.begin(); other != out; ++other) {
            if (given(*other) && same_file(out->path, other->path)) {
                throw InputError(fmt::format("{} {}: is also the output of {}; give two different files", out->option, naming(*out, *other), other->option));
            }
        }
        check_writable(*out);
    }
}

void check_output_directory(const NamedPath& directory, const std::vector<NamedPath>& files) {
    if (directory.path.empty()) return;
    for (const NamedPath& f : files) {
        if (!given(f)) continue;
        const fs::path p(f.path);
        const bool written_by_report = p.filename() == "report.md" || p.extension() == ".png";
        if (written_by_report && same_file(p.parent_path().empty() ? fs::path(".") : p.parent_path(), directory.path)) {
            throw InputError(fmt::format("{} {}: the report writes report.md and PNG plots in it, and {} is the file given to {}; give another folder",
                                         directory.option, directory.path, f.path, f.option));
        }
    }
    std::error_code ec;
    if (fs::exists(directory.path, ec) && !fs::is_directory(directory.path, ec)) {
        throw InputError(fmt::format("{} {}: exists and is not a directory", directory.option, directory.path));
    }
    // The folders that do not exist yet, innermost first, to remove them again after the try.
    std::vector<fs::path> created;
    for (fs::path p = fs::absolute(directory.path, ec).lexically_normal(); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        created.push_back(p);
        if (p == p.parent_path()) break;
    }
    auto remove_created = [&] {
        for (const fs::path& p : created) fs::remove(p, ec);
    };
    fs::create_directories(directory.path, ec);
    if (ec) {
        const std::string why = ec.message();
        remove_created();
        throw InputError(fmt::format("{} {}: cannot create the directory: {}", directory.option, directory.path, why));
    }
    const fs::path probe = fs::path(directory.path) / ".jacobid-write-check";
    std::FILE* f = std::fopen(probe.c_str(), "wb");
    const int err = errno;
    if (f) {
        std::fclose(f);
        fs::remove(probe, ec);
    }
    remove_created();
    if (!f) throw InputError(fmt::format("{} {}: cannot write in the directory: {}", directory.option, directory.path, std::strerror(err)));
}

void prepare_output_directory(const NamedPath& directory) {
    std::error_code ec;
    if (fs::exists(directory.path, ec) && !fs::is_directory(directory.path, ec)) {
        throw InputError(fmt::format("{} {}: exists and is not a directory", directory.option, directory.path));
    }
    fs::create_directories(directory.path, ec);
    if (ec) throw InputError(fmt::format("{} {}: cannot create the directory: {}", directory.option, directory.path, ec.message()));
}

void write_output(const std::string& path, const std::string& text) {
    if (path == "-") {
        const bool written = std::fwrite(text.data(), 1, text.size(), stdout) == text.size();
        if (std::fflush(stdout) != 0 || !written) throw InputError(fmt::format("standard output: write failed: {}", std::strerror(errno)));
        return;
    }
    std::ofstream out(path, std::ios::binary);
    if (!out) throw InputError(fmt::format("{}: cannot open for writing", path));
    out << text;
    out.close();  // the last block reaches the file (or fails: a full disk) here
    if (!out) throw InputError(fmt::format("{}: write failed (disk full?)", path));
}

}  // namespace jacobid::options
