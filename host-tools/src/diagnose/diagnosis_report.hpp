// SPDX-License-Identifier: MIT
#pragma once
// Output of `jacobid diagnose`: a text summary (tables of the named effects and of the gap before and
// after), JSON ({"effects": [...], "before": {...}, "after": {...}, ...}) and a Markdown report with PNG
// plots of the residual against velocity and position before and after.
#include <nlohmann/json.hpp>
#include <string>

#include "diagnose/diagnosis.hpp"

namespace jacobid::diagnose {

std::string format_text(const Diagnosis& d);
nlohmann::json to_json(const Diagnosis& d);
// Writes DIR/report.md, DIR/residual_velocity.png and DIR/residual_position.png. InputError if DIR cannot be
// created; std::runtime_error if gnuplot fails.
void write_report(const std::string& directory, const Diagnosis& d);

}  // namespace jacobid::diagnose
