// SPDX-License-Identifier: MIT
#pragma once
// Parses and runs a command line whose subcommands the caller added (main.cpp: every command; cli/board_main.cpp:
// the board's subset), with the conventions of cli/command.hpp: "jacobid <command>: error: <message>" on one
// line and kExitInputError for bad input, an unknown first word named with the commands there are,
// kExitInternalError for anything else. Returns the exit status.
namespace CLI {
class App;
}

namespace jacobid::cli {

int run_command_line(CLI::App& app, int argc, char** argv);

}  // namespace jacobid::cli
