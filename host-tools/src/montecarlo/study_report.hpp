// SPDX-License-Identifier: MIT
#pragma once
// The outputs of `jacobid montecarlo` (docs/montecarlo.md): the per-parameter table as text, the JSON with
// every run's estimates, and DIR/report.md with one PNG per method.
#include <nlohmann/json.hpp>
#include <string>

#include "montecarlo/study.hpp"
#include "montecarlo/summary.hpp"

namespace jacobid::montecarlo {

// What the outputs say about where the study came from.
struct StudyContext {
    std::string robot;          // the description's file, or "built-in planar2r"
    nlohmann::json settings;    // the command's settings (runs, seeds, simulation, identification)
    std::string settings_line;  // the same in one line for the text table and report.md
    Acceptance acceptance;
};

std::string format_table(const Study& study, const StudyContext& context);
nlohmann::json to_json(const Study& study, const StudyContext& context);
// DIR/report.md (the table) and DIR/montecarlo_<method>.png. InputError if DIR cannot be written.
void write_report(const std::string& directory, const Study& study, const StudyContext& context);

}  // namespace jacobid::montecarlo
