// SPDX-License-Identifier: MIT
#pragma once
// identify --export-urdf FILE / --export-robot FILE (identify/report/model_export.hpp): the options and writing the files.
#include <nlohmann/json.hpp>
#include <string>

#include "identify/report/model_export.hpp"

namespace CLI {
class App;
}

namespace jacobid::options {

void add_model_export_options(CLI::App* command, identify::ModelExportPaths& paths);

// Writes the files asked for from `result`; returns the JSON "export" summary. InputError naming the option
// when a file cannot be written.
nlohmann::json write_model_export(const identify::ModelExportPaths& paths, const robot::RobotDescription& description,
                                  const identify::MethodResult& result, const std::string& log_source);

}  // namespace jacobid::options
