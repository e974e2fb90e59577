// SPDX-License-Identifier: MIT
// jacobid-fw configuration (fwconfig/src/firmware_config_yaml.cpp): any text must either parse or raise
// ConfigError (one line naming file, line, column and key), never another exception or a crash.
// Property of an accepted configuration: its joints configure the HAL decoder set without error (the
// parser promises to report a bad decoder setting by key, not leave it to start-up), within kMaxJoints.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_check.hpp"
#include "jacobid/fwconfig/firmware_config_yaml.hpp"

using namespace jacobid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    firmware::FirmwareConfig config;
    try {
        config = firmware::parse_firmware_config(text, "fw.yaml");
    } catch (const firmware::ConfigError&) {
        return 0;
    }
    JACOBID_FUZZ_CHECK(!config.joints.empty() && config.joints.size() <= firmware::kMaxJoints, "accepted joint count outside 1..kMaxJoints");
    JACOBID_FUZZ_CHECK(config.rate > 0.0, "accepted a non-positive rate");
    std::vector<hal::ProfileConfig> decoders;
    for (const firmware::JointConfig& j : config.joints) decoders.push_back(j.decoder);
    hal::JointDecoderSet<firmware::kMaxJoints> set;
    const hal::DecoderSetConfigResult r = set.configure(Span<const hal::ProfileConfig>(decoders.data(), decoders.size()), config.max_age);
    JACOBID_FUZZ_CHECK(r.status == hal::ConfigStatus::Ok, "an accepted configuration has a decoder the HAL rejects");
    return 0;
}
