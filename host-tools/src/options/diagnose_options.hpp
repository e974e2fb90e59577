// SPDX-License-Identifier: MIT
#pragma once
// The options of the diagnosis' search (--alpha, --min-gain, --max-effects, --folds, --max-delay, --no-delay,
// --max-cogging-order, --horizon, --horizon-spacing and the pipeline rates), shared by `jacobid diagnose` and
// the Python module's jacobid.diagnose().
#include "diagnose/diagnosis.hpp"
#include "identify/plan/log_columns.hpp"
#include "robot/robot_model.hpp"

namespace CLI {
class App;
}

namespace jacobid::options {

void add_diagnose_search_options(CLI::App* cmd, diagnose::DiagnoseSettings& settings, bool& no_delay);

// The search's sizes that follow from the settings and the log (folds, delay candidates, cogging candidates),
// refused with an InputError naming the option before the search allocates them. `total_samples`: of every
// log diagnosed together (0: `log`'s).
void refuse_oversized_search(const diagnose::DiagnoseSettings& settings, const identify::LogColumns& log, const robot::RobotModel& model,
                             std::size_t total_samples = 0);

}  // namespace jacobid::options
