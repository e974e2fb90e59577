// SPDX-License-Identifier: MIT
// jacobid: the host-side command line. Subcommands are defined in src/cli/*_command.cpp.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <exception>
#include <string>

#include "cli/command.hpp"
#include "io/printable_text.hpp"

namespace {

// "jacobid <command>: error: <message>" on one line: the subcommand being read, if any.
int report_input_error(const CLI::App& app, std::string message) {
    std::replace(message.begin(), message.end(), '\n', ' ');
    const auto subcommands = app.get_subcommands();
    const std::string command = subcommands.empty() ? std::string() : " " + subcommands.front()->get_name();
    // The last safety net for user text a message quotes without io::printable_cell: control and invisible
    // characters escaped, a message of a huge token cut (io/printable_text.hpp).
    fmt::print(stderr, "jacobid{}: error: {}\n", command, jacobid::io::printable_message(message));
    return jacobid::kExitInputError;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"jacobid: robot dynamic identification with the Jacobi differentiator"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "jacobid 0.1.0");
    jacobid::cli::add_kernel_command(app);
    jacobid::cli::add_simulate_command(app);
    jacobid::cli::add_identify_command(app);
    jacobid::cli::add_bode_command(app);
    jacobid::cli::add_differentiate_command(app);
    jacobid::cli::add_paper_sines_command(app);
    jacobid::cli::add_record_command(app);
    jacobid::cli::add_sim_can_command(app);
    jacobid::cli::add_diagnose_command(app);
    jacobid::cli::add_montecarlo_command(app);
#if JACOBID_WITH_NLOPT
    jacobid::cli::add_excite_command(app);
#endif

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
    } catch (const jacobid::InputError& e) {
        return report_input_error(app, e.what());
    } catch (const std::exception& e) {
        fmt::print(stderr, "jacobid: internal error: {}\n", e.what());
        return jacobid::kExitInternalError;
    }
    return jacobid::kExitOk;
}
