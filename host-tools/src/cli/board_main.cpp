// SPDX-License-Identifier: MIT
// jacobid-board: the commands of jacobid that run on the controller board itself, nothing that identifies:
// sim-can (simulated drives on the board's CAN bus) and record (the estimate stream into a CSV). The emulated
// board of scripts/vm-test.sh runs it as `jacobid`; the recorded log is identified on the PC, by the full
// jacobid. It links jacobid::host_base only, so a cross build compiles half of the host sources.
#include <CLI/CLI.hpp>

#include "cli/command.hpp"
#include "cli/command_line.hpp"

int main(int argc, char** argv) {
    CLI::App app{"jacobid-board: the board's jacobid commands (sim-can, record); identification runs on the PC (jacobid identify)"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "jacobid-board 0.1.0");
    jacobid::cli::add_record_command(app);
    jacobid::cli::add_sim_can_command(app);
    return jacobid::cli::run_command_line(app, argc, argv);
}
