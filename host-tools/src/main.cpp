// SPDX-License-Identifier: MIT
// jacobid: the host-side command line. Subcommands are defined in src/cli/*_command.cpp.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <exception>

#include "cli/command.hpp"

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

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const jacobid::InputError& e) {
        const auto* sub = app.get_subcommands().empty() ? nullptr : app.get_subcommands().front();
        fmt::print(stderr, "jacobid {}: error: {}\n", sub ? sub->get_name() : "", e.what());
        return jacobid::kExitInputError;
    } catch (const std::exception& e) {
        fmt::print(stderr, "jacobid: internal error: {}\n", e.what());
        return jacobid::kExitInternalError;
    }
    return jacobid::kExitOk;
}
