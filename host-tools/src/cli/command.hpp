// SPDX-License-Identifier: MIT
#pragma once
// Conventions shared by the jacobid subcommands.
//
// Each command lives in its own file and exposes `void add_<name>_command(CLI::App& app)`, which adds the
// subcommand, its options and a callback. Callbacks report bad input by throwing jacobid::InputError
// with a one-line message that names the file, line, column or parameter; main() prints it as
// "jacobid <command>: error: <message>" and exits with kExitInputError.
#include "core/errors.hpp"

namespace CLI {
class App;
}

namespace jacobid::options {}  // the option declarations the commands share (host-tools/src/options/)

namespace jacobid::cli {

// The commands are written in terms of the shared option declarations, which the Python module uses too.
using namespace jacobid::options;

void add_kernel_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_identify_command(CLI::App& app);
void add_bode_command(CLI::App& app);
void add_differentiate_command(CLI::App& app);
void add_paper_sines_command(CLI::App& app);
void add_record_command(CLI::App& app);
void add_sim_can_command(CLI::App& app);
void add_diagnose_command(CLI::App& app);
void add_montecarlo_command(CLI::App& app);
void add_payload_command(CLI::App& app);
void add_monitor_command(CLI::App& app);
// Built only with NLopt (JACOBID_WITH_NLOPT).
void add_excite_command(CLI::App& app);

}  // namespace jacobid::cli
