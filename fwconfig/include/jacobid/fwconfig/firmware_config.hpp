// SPDX-License-Identifier: MIT
#pragma once
// Configuration of the jacobid firmware (jacobid-fw): plain structs, separate from the cycle's state
// (Moteus/Pinocchio style: the config is read once at start-up, FirmwareCycle only reads it).
//
// Parsing (YAML, with file:line:column errors) lives in firmware_config_yaml.hpp so that this header stays
// free of yaml-cpp: the simulator side (jacobid sim-can) includes it for the profile defaults below, which
// is what keeps `sim-can --profile mit` and a firmware joint written as `{profile: mit}` on the same wire
// encoding. The profiles themselves (names, defaults, keys) come from hal/profile_registry.hpp.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "jacobid/fwconfig/capacity.hpp"
#include "jacobid/fwconfig/monitor_config.hpp"
#include "jacobid/fwconfig/playback_config.hpp"
#include "jacobid/hal/joint_decoder_set.hpp"
#include "jacobid/kernel_params.hpp"

namespace jacobid::firmware {

struct JointConfig {
    std::string name;
    hal::ProfileConfig decoder;  // the HAL profile configuration, link-side mapping included (hal::profile_name)
};

// The Jacobi differentiators of the streaming bank (one design for every joint).
struct EstimatorConfig {
    double position_window = 0.02;      // s, n = 0 (q^)
    double velocity_window = 0.05;      // s, n = 1 (qd^)
    double acceleration_window = 0.10;  // s, n = 2 (qdd^)
    double kappa = 6.0, mu = 6.0;
    int q = 2;
    double xi = 0.0;  // 0: central (delayed by half the longest window), 1: causal
    Discretization discretization = Discretization::Exact;
};

struct StreamConfig {
    std::string host = "127.0.0.1";
    std::uint16_t port = 5005;
    std::string log;  // optional local copy: the datagrams back to back (each is self-delimiting)
};

struct GpioConfig {
    bool enabled = false;  // no `gpio:` section: no safety I/O (the stream never carries the e-stop flag)
    std::string chip = "gpiochip0";
    unsigned estop_line = 0;
    unsigned enable_line = 0;
    unsigned sync_line = 0;
    bool estop_active_low = true;
    bool enable_active_low = false;
};

struct RealtimeConfig {
    int priority = 80;           // SCHED_FIFO priority; 0: do not ask for SCHED_FIFO
    int cpu = -1;                // CPU to pin the cycle thread to; -1: no affinity
    bool lock_memory = true;     // mlockall(MCL_CURRENT | MCL_FUTURE)
    double report_period = 10.0; // s between jitter/summary lines on stderr; 0: only at exit
};

struct FirmwareConfig {
    std::string source = "<defaults>";
    std::string can_interface = "can0";  // "virtual": in-process bus with no device (dry run)
    // CANopen SYNC (CiA 301): a zero-length frame with this standard id, sent in every cycle right after
    // the bus is read. Drives with synchronous TPDOs (and `jacobid sim-can`) answer it, so each sample
    // lands in the next cycle whatever the drives' own clocks do. -1: no SYNC (drives free-run).
    std::int32_t sync_id = -1;
    double rate = 1000.0;                // Hz
    std::uint32_t max_age = 0;           // cycles a joint value may be late before it is stale (0: every cycle)
    std::vector<JointConfig> joints;
    EstimatorConfig estimator;
    StreamConfig stream;
    GpioConfig gpio;
    RealtimeConfig realtime;
    // `trajectory:` given: the cycle plays it on the drives (TrajectoryPlayer); else it only measures.
    bool playback = false;
    PlaybackConfig trajectory;
    // `monitor:` given: the cycle estimates the external torque and acts on a contact (issue 40).
    MonitorConfig monitor;

    double sample_period() const noexcept { return 1.0 / rate; }
};

// The kernel parameters of channel c (0 q^, 1 qd^, 2 qdd^) for a given estimator config and rate.
KernelParams kernel_params(const EstimatorConfig& e, double sample_period, int channel) noexcept;

// The names fw.yaml offers for `profile:` (the registry's profiles with kInFirmwareConfig), in order.
std::vector<std::string> firmware_profile_names();

// Defaults of a joint given only its profile name and its index (0-based): the same on the firmware and
// the simulator side, each profile's apply_firmware_defaults (hal/profiles/*.hpp; why these values:
// docs/firmware.md, "Profiles and resolution"). False when fw.yaml offers no profile of that name.
bool default_profile_config(const std::string& profile, std::size_t index, hal::ProfileConfig& out);

}  // namespace jacobid::firmware
