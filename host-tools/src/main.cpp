// SPDX-License-Identifier: MIT
// jacobid: the host-side command line. Subcommands are defined in src/cli/*_command.cpp.
#include <CLI/CLI.hpp>

#include "cli/command.hpp"
#include "cli/command_line.hpp"

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
    jacobid::cli::add_payload_command(app);
    jacobid::cli::add_monitor_command(app);
#if JACOBID_WITH_NLOPT
    jacobid::cli::add_excite_command(app);
#endif
    return jacobid::cli::run_command_line(app, argc, argv);
}
