#pragma once
// Conventions shared by the jacobid subcommands.
//
// Each command lives in its own file and exposes `void add_<name>_command(CLI::App& app)`, which adds the
// subcommand, its options and a callback. Callbacks report bad input by throwing jacobid::cli::InputError
// with a one-line message that names the file, line, column or parameter; main() prints it as
// "jacobid <command>: error: <message>" and exits with kExitInputError.
#include <stdexcept>
#include <string>

namespace CLI {
class App;
}

namespace jacobid::cli {

constexpr int kExitOk = 0;
constexpr int kExitInputError = 2;    // bad file, bad parameter, data that cannot be used
constexpr int kExitInternalError = 3;  // a bug or an environment problem (e.g. gnuplot missing)

struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void add_kernel_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_identify_command(CLI::App& app);
void add_bode_command(CLI::App& app);
void add_differentiate_command(CLI::App& app);
void add_paper_sines_command(CLI::App& app);
void add_record_command(CLI::App& app);
void add_sim_can_command(CLI::App& app);
void add_diagnose_command(CLI::App& app);

}  // namespace jacobid::cli
