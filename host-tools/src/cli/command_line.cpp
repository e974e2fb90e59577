// SPDX-License-Identifier: MIT
#include "cli/command_line.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <exception>
#include <string>

#include "cli/command.hpp"
#include "io/printable_text.hpp"

namespace jacobid::cli {
namespace {

// "jacobid <command>: error: <message>" on one line: the subcommand being read, if any.
int report_input_error(const CLI::App& app, std::string message) {
    std::replace(message.begin(), message.end(), '\n', ' ');
    const auto subcommands = app.get_subcommands();
    const std::string command = subcommands.empty() ? std::string() : " " + subcommands.front()->get_name();
    // The last safety net for user text a message quotes without io::printable_cell: control and invisible
    // characters escaped, a message of a huge token cut (io/printable_text.hpp).
    fmt::print(stderr, "jacobid{}: error: {}\n", command, io::printable_message(message));
    return kExitInputError;
}

}  // namespace

int run_command_line(CLI::App& app, int argc, char** argv) {
    // A first word that is no command: CLI11 would only say "A subcommand is required"; name the word and the
    // commands there are.
    if (argc > 1 && argv[1][0] != '-') {
        const std::string word = argv[1];
        const auto commands = app.get_subcommands([](const CLI::App*) { return true; });
        const bool known = std::any_of(commands.begin(), commands.end(), [&](const CLI::App* c) { return c->check_name(word); });
        if (!known) {
            std::string names;
            for (const CLI::App* c : commands) names += (names.empty() ? "" : ", ") + c->get_name();
            return report_input_error(app, "unknown command '" + word + "'; the commands are: " + names + " (jacobid --help)");
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);  // --help, --help-all, --version: printed, exit 0
    } catch (const CLI::ParseError& e) {
        // An unknown option, a missing or unconvertible value, a validator's refusal: bad input like any other.
        return report_input_error(app, e.what());
    } catch (const InputError& e) {
        return report_input_error(app, e.what());
    } catch (const std::exception& e) {
        fmt::print(stderr, "jacobid: internal error: {}\n", e.what());
        return kExitInternalError;
    }
    return kExitOk;
}

}  // namespace jacobid::cli
