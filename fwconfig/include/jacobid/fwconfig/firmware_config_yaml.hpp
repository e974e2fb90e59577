// SPDX-License-Identifier: MIT
#pragma once
// fw.yaml -> FirmwareConfig. Every error is a ConfigError whose one-line message names the file, the line
// and column, and the key ("fw.yaml:7:17: joints[1].gear_ratio: must be finite and non-zero"); unknown
// keys are errors too, so a typo never silently falls back to a default. Example: docs/firmware.md.
#include <stdexcept>
#include <string>

#include "jacobid/fwconfig/firmware_config.hpp"

namespace jacobid::firmware {

struct ConfigError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

FirmwareConfig load_firmware_config(const std::string& path);
FirmwareConfig parse_firmware_config(const std::string& yaml_text, const std::string& source);

}  // namespace jacobid::firmware
