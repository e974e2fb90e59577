// SPDX-License-Identifier: MIT
#pragma once
// Writing command results: '-' is standard output, anything else a file (InputError if it cannot be
// written, naming the path).
#include <initializer_list>
#include <string>
#include <vector>

namespace jacobid::options {

// A file a command reads or writes, with the option that named it ("--in", "-o", ...).
struct NamedPath {
    std::string option;
    std::string path;  // empty: not given (skipped); "-": standard output
};

// The one guard of every command's outputs (issue 36): called with all the files the command reads and all
// it writes, before any output is opened. Checks that each output can be written: its directory exists, it
// is not a directory, the file can be created or opened for writing (tried without truncating; a file
// created for the try is removed again), and it is neither one of the inputs nor another output (a result
// written over the log or the URDF it came from). Paths are compared as files (jacobid::same_file: a
// symlink or hard link to an input is that input). InputError naming both options and the file otherwise.
void check_outputs(std::initializer_list<NamedPath> outputs, std::initializer_list<NamedPath> inputs = {});
// The same with a list of inputs built at run time (identify --in a --in b ...).
void check_outputs(std::initializer_list<NamedPath> outputs, const std::vector<NamedPath>& inputs);
// And with a list of outputs built at run time (the identify job's files beside its caller's --output).
void check_outputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs);

// Checks, before any work is done, that an output folder (--report DIR) can be written: it is a directory
// or can be created, and a file can be created in it. What the check created is removed again (the
// folder is made when the report is written). `files`: the others the command reads or writes; none may be
// one the report writes in the folder (its report.md or a PNG plot). InputError naming the option and the path otherwise.
void check_output_directory(const NamedPath& directory, const std::vector<NamedPath>& files = {});

// Checks an output folder (paper-sines --out-dir): it exists as a directory or is created now.
void prepare_output_directory(const NamedPath& directory);

// Writes `text`; a failed write, flush or close (a full disk, /dev/full) is an InputError.
void write_output(const std::string& path, const std::string& text);

}  // namespace jacobid::options
