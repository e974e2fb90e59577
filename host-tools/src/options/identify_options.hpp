// SPDX-License-Identifier: MIT
#pragma once
// The options of an identification (`jacobid identify` and the Python module's jacobid.identify()): one
// declaration, so that a keyword of the module is the command line's option of the same name, checked by the
// same validators. What only the command line has (--robot, --in, --format, --output, --print-base, --truth,
// --validate as files) is declared by the command itself.
#include <string>
#include <vector>

#include "identify/report/model_export.hpp"
#include "identify/physical/physical_identification.hpp"
#include "io/time_axis.hpp"
#include "options/drive_gains_options.hpp"
#include "options/fit_options.hpp"
#include "options/log_format_options.hpp"

namespace CLI {
class App;
}

namespace jacobid::options {

// FitOptions: how each log is identified (fit_options.hpp, shared with montecarlo).
struct IdentifyOptions : FitOptions {
    std::vector<std::string> inputs;  // --in, once or more (names for messages when the logs are given as tables)
    std::string validate;             // --validate (a name, when the log is given as a table)
    std::string truth;                // --truth (the file's name, for messages)
    std::string robot;                // --robot (the file's name, for messages)
    int threads = 0;                  // --threads: logs identified at once (0: one per core)
    std::string method = "jacobi";
    std::string report;
    std::string time_column = "t";
    double essential = 0.0;  // threshold in %; 0: off
    bool essential_flag = false;
    bool quiet = false;
    double time_tolerance = io::kDefaultTimeTolerance;
    std::string can_config;
    std::string velocity;  // measured | jacobi | butterworth; empty: the method's own
    LogFormatOptions log_format;
    bool physical = false;       // --physical
    bool semi_physical = false;  // --semi-physical
    double prior_weight = identify::PhysicalSettings{}.prior_weight;
    identify::ModelExportPaths model_export;  // --export-urdf, --export-robot
    DriveGainOptions drive_gains;             // --drive-gains --loaded --payload-mass ...
    std::string period;                       // --period auto|SECONDS; empty: off
    std::size_t piece_rows = 0;               // --piece-rows; 0: automatic (job/streamed_log.hpp)
    bool text_on_stdout = false;  // the text output goes to the terminal: a line it starts with is not also printed on stderr

    const std::string& first_input() const;  // the first --in (the one log, or the first of several); empty: none
};

// Every option of IdentifyOptions but the files (--in, --validate, --truth, --robot): --piece-rows, --threads,
// --method, --report, --time-column, --time-tolerance, --can-config, the log format's, the fit's, --velocity,
// --essential, --physical, --semi-physical, --prior-weight, --export-urdf, --export-robot, the drive gains',
// --period, --quiet.
void add_identify_options(CLI::App* cmd, IdentifyOptions& o);

// After parsing: --essential without a value is 10 %, --discretization resolved into the pipeline.
void finish_identify_options(IdentifyOptions& o);

}  // namespace jacobid::options
