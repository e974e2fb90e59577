// SPDX-License-Identifier: MIT
#include "jacobid/fwconfig/firmware_config_yaml.hpp"

#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <array>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "jacobid/differentiator_bank.hpp"
#include "jacobid/fwconfig/playback_checks.hpp"
#include "jacobid/fwconfig/trajectory_table.hpp"
#include "jacobid/hal/profile_registry.hpp"
#include "jacobid/yaml/yaml_section.hpp"
#include "jacobid/yaml/input_file.hpp"
#include "can_id_checks.hpp"
#include "drive_reading.hpp"
#include "output_files.hpp"

namespace jacobid::firmware {
namespace {

using Section = yaml::YamlSection<ConfigError>;

constexpr double kMinRate = 1.0, kMaxRate = 10000.0;  // Hz
constexpr double kMinReportPeriod = 0.1;               // s
constexpr double kMaxSeconds = 1e9;                    // s, as jacobid-fw --duration
constexpr double kMaxRampTime = 3600.0;                // s

// "a, b or c" for the missing-key message.
std::string one_of(const std::vector<std::string>& names) {
    std::string all;
    for (std::size_t i = 0; i < names.size(); ++i) all += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return all;
}

// A joint: its profile's defaults, then the profile's own keys (read_config in hal/profiles/*.hpp),
// then the HAL's validation reported at the key it is about (config_key_of). Which profiles exist is
// the registry's business (hal/profile_registry.hpp): no profile is named here.
JointConfig read_joint(const std::string& source, const YAML::Node& node, std::size_t index) {
    Section s(source, node, fmt::format("joints[{}]", index));
    JointConfig j;
    j.name = s.text("name", fmt::format("j{}", index + 1));
    const std::vector<std::string> names = firmware_profile_names();
    if (!s.has("profile")) s.fail(node, "profile", "missing (required): " + one_of(names));
    const std::string profile = s.choice("profile", "", names);
    hal::with_profile_named(profile.c_str(), [&](auto tag) {
        using P = typename decltype(tag)::type;
        if constexpr (P::kInFirmwareConfig) {
            typename P::Config c;
            apply_firmware_defaults(c, index);
            read_config(s, c);
            s.reject_unknown();
            if (const hal::ConfigStatus st = validate(c); st != hal::ConfigStatus::Ok) s.fail(config_key_of(c, st), hal::describe(st));
            j.decoder = c;
        }
    });
    return j;
}

void read_estimator(Section& s, EstimatorConfig& e, double rate) {
    e.position_window = s.positive("position_window", e.position_window);
    e.velocity_window = s.positive("velocity_window", e.velocity_window);
    e.acceleration_window = s.positive("acceleration_window", e.acceleration_window);
    e.kappa = s.number("kappa", e.kappa);
    e.mu = s.number("mu", e.mu);
    e.q = static_cast<int>(s.integer("q", e.q, 0, kMaxDegree - 2));
    e.xi = s.number("xi", e.xi);
    e.discretization = s.choice("discretization", "exact", {"exact", "trapezoidal"}) == "exact" ? Discretization::Exact : Discretization::Trapezoidal;
    s.reject_unknown();
    static constexpr const char* kKeys[] = {"position_window", "velocity_window", "acceleration_window"};
    std::array<JointFilterConfig, 1> filters{};
    for (int c = 0; c < kChannelCount; ++c) {
        const KernelParams p = kernel_params(e, 1.0 / rate, c);
        const KernelStatus ks = validate(p, kKernelCapacity);
        const char* key = ks == KernelStatus::InvalidKappa ? "kappa" : ks == KernelStatus::InvalidMu ? "mu" : ks == KernelStatus::InvalidXi ? "xi" : kKeys[c];
        if (ks != KernelStatus::Ok) s.fail(key, fmt::format("{} (at {} Hz; at most {} taps)", describe(ks), rate, kKernelCapacity));
        filters[0].params[static_cast<std::size_t>(c)] = p;
    }
    // The bank is large: try the design on the heap (start-up only) for the alignment checks.
    auto bank = std::make_unique<DifferentiatorBank<double, 1, kKernelCapacity>>();
    const BankConfigResult r = bank->configure(filters);
    if (r.status != BankStatus::Ok) {
        std::string why = describe(r.status);
        if (r.status == BankStatus::InvalidKernel) why += std::string(": ") + describe(r.kernel_status);
        s.fail(kKeys[r.channel], why);
    }
}

// A path in fw.yaml is relative to the file's own folder (the config and its trajectory travel together).
std::string relative_to(const std::string& source, const std::string& path) {
    if (path.empty() || path.front() == '/') return path;
    const std::size_t slash = source.find_last_of('/');
    return slash == std::string::npos ? path : source.substr(0, slash + 1) + path;
}

// monitor: {robot, thresholds, action, stream} (docs/firmware.md, "Contact monitor"). The two files are read
// at start-up by the host's own readers (jacobid-fw's main; tests call the same loader), not here: this library
// stays free of the robot description's reader.
void read_monitor(Section& s, FirmwareConfig& c) {
    MonitorConfig& m = c.monitor;
    m.robot = relative_to(c.source, s.required_text("robot"));
    m.thresholds = relative_to(c.source, s.required_text("thresholds"));
    m.action = s.choice("action", "stop", {"stop", "flag"}) == "stop" ? MonitorAction::Stop : MonitorAction::Flag;
    m.stream = s.boolean("stream", true);
    s.reject_unknown();
    m.enabled = true;
}

// trajectory: {file, mode, ramp_time, repeat, max_stale_cycles, joints: [{position, velocity, acceleration, torque,
// following_error, kp, kd}, ...]} (docs/firmware.md, "Trajectory playback"). Every limit is required: a
// robot is never moved within limits the file did not state.
void read_trajectory(Section& s, const YAML::Node& node, FirmwareConfig& c) {
    PlaybackConfig& p = c.trajectory;
    p.file = relative_to(c.source, s.required_text("file"));
    p.log = relative_to(c.source, s.text("log", ""));
    p.mode = s.choice("mode", "position", {"position", "torque"}) == "position" ? hal::CommandMode::Position : hal::CommandMode::Torque;
    p.ramp_time = s.positive("ramp_time", p.ramp_time, "s");
    // An hour is no ramp anyone means (ms written as s?); far longer ones overflow the ramp's cycle count.
    if (p.ramp_time > kMaxRampTime) s.fail("ramp_time", fmt::format("{:g} s: expected at most {:g} s (in seconds, not ms)", p.ramp_time, kMaxRampTime));
    p.repeat = static_cast<int>(s.integer("repeat", p.repeat, 1, 1'000'000));
    p.max_stale_cycles = static_cast<std::uint32_t>(s.integer("max_stale_cycles", 0, 0, 1000));
    if (!s.has("joints")) s.fail(node, "joints", "missing (required): one entry of limits per joint");
    const YAML::Node joints = s.list("joints", c.joints.size(), c.joints.size(), "limits (one per joint of `joints:`)");
    for (std::size_t j = 0; j < joints.size(); ++j) {
        Section limits(c.source, joints[j], fmt::format("trajectory.joints[{}]", j));
        for (const char* key : {"position", "velocity", "acceleration", "torque", "following_error"}) {
            if (!limits.has(key)) limits.fail(joints[j], key, "missing (required): this joint's limit");
        }
        const auto [lo, hi] = limits.range("position", {0.0, 0.0}, "rad");
        p.position_min[j] = lo;
        p.position_max[j] = hi;
        p.velocity_limit[j] = limits.positive("velocity", 0.0, "rad/s");
        p.acceleration_limit[j] = limits.positive("acceleration", 0.0, "rad/s^2");
        p.torque_limit[j] = limits.positive("torque", 0.0, "N.m");
        p.following_error[j] = limits.positive("following_error", 0.0, "rad");
        p.kp[j] = limits.number("kp", 0.0, "N.m/rad");
        p.kd[j] = limits.number("kd", 0.0, "N.m.s/rad");
        if (p.kp[j] < 0.0) limits.fail("kp", "must be >= 0");
        if (p.kd[j] < 0.0) limits.fail("kd", "must be >= 0");
        // A following error as wide as the position range could never stop the playback.
        if (!(p.following_error[j] < hi - lo)) {
            limits.fail("following_error", fmt::format("{} rad is not below the width of the position limits, {} rad: it could never stop the "
                                                       "playback", p.following_error[j], hi - lo));
        }
        if (p.mode == hal::CommandMode::Position && !reads_position_commands(c.joints[j].decoder, p.kp[j], p.kd[j])) {
            limits.fail(joints[j], "kp", fmt::format("with kp: {} and kd: {} joints[{}]'s {} drive reads each position command as a torque command "
                                                     "and holds no position (nor the stop); give the drive's own gains kp and kd",
                                                     p.kp[j], p.kd[j], j, hal::profile_name(c.joints[j].decoder)));
        }
        // A limit the command frames cannot carry: a command there would reach the drive saturated.
        if (const std::optional<UncarriedLimit> u = uncarried_limit(c.joints[j].decoder, p, j)) {
            limits.fail(u->key, fmt::format("{:g} cannot be sent to joints[{}]'s {} drive: its command frames carry {:g} there (the encoder "
                                            "saturates); keep the limit within what the profile's ranges and gear ratio allow",
                                            u->asked, j, hal::profile_name(c.joints[j].decoder), u->carried));
        }
        limits.reject_unknown();
    }
    s.reject_unknown();
    p.rows = load_trajectory_table(p.file, c.joints.size(), c.rate, p.mode == hal::CommandMode::Torque);
    // The same check the player makes before its first command, here so that jacobid-fw refuses an unsafe
    // table before it opens a device or an output file; the message names the table's file:line itself.
    if (std::string why = check_playback(p, c.joints.size(), c.sample_period()); !why.empty()) throw ConfigError(why);
    c.playback = true;
}

FirmwareConfig read_config(const YAML::Node& root, const std::string& source) {
    FirmwareConfig c;
    c.source = source;
    Section top(source, root, "");
    c.rate = top.positive("rate", c.rate, "Hz");
    // Beyond these the rate only gives wrong messages or undefined arithmetic: above 10 kHz the cycle cannot
    // meet its bus (a 1 Mbit/s CAN bus carries about 8000 classic frames a second), and the estimator
    // windows would be blamed; below 1 Hz the loop's period in ns approaches what int64 holds.
    if (c.rate < kMinRate || c.rate > kMaxRate) top.fail("rate", fmt::format("{:g} Hz: expected a control rate in [{:g}, {:g}] Hz", c.rate, kMinRate, kMaxRate));
    c.max_age = static_cast<std::uint32_t>(top.integer("max_age", c.max_age, 0, 1000));

    top.mark_used("can");
    if (!top.has("can")) top.fail(root, "can", "missing (required): can: {interface: can0}");
    Section can(source, top.get("can"), "can");
    c.can_interface = can.required_text("interface");
    if (c.can_interface.empty()) can.fail("interface", "must not be empty");
    if (can.has("sync_id")) c.sync_id = static_cast<std::int32_t>(can.integer("sync_id", 0x80, 1, hal::kCanStandardIdMask));
    can.reject_unknown();

    top.mark_used("joints");
    const YAML::Node joints = top.get("joints");
    if (!joints.IsDefined() || joints.IsNull()) top.fail(root, "joints", "missing (required): a list of joints");
    if (!joints.IsSequence() || joints.size() == 0) top.fail("joints", "must be a non-empty list");
    if (joints.size() > kMaxJoints) top.fail("joints", fmt::format("at most {} joints", kMaxJoints));
    for (std::size_t i = 0; i < joints.size(); ++i) c.joints.push_back(read_joint(source, joints[i], i));
    require_distinct_devices(source, joints, c.joints);
    if (c.sync_id >= 0) require_sync_id_unused(source, top.get("can")["sync_id"], static_cast<std::uint32_t>(c.sync_id), joints, c.joints);

    top.mark_used("estimator");
    if (top.has("estimator")) {
        Section e(source, top.get("estimator"), "estimator");
        read_estimator(e, c.estimator, c.rate);
    } else {
        Section e(source, YAML::Load("{}"), "estimator");
        read_estimator(e, c.estimator, c.rate);
    }

    top.mark_used("stream");
    if (!top.has("stream")) top.fail(root, "stream", "missing (required): stream: {host: 127.0.0.1, port: 5005}");
    Section st(source, top.get("stream"), "stream");
    c.stream.host = st.required_text("host");
    if (!st.has("port")) st.fail(top.get("stream"), "port", "missing (required)");
    c.stream.port = static_cast<std::uint16_t>(st.integer("port", 0, 1, 65535));
    c.stream.log = relative_to(source, st.text("log", ""));
    st.reject_unknown();

    top.mark_used("gpio");
    if (top.has("gpio")) {
        Section g(source, top.get("gpio"), "gpio");
        c.gpio.enabled = true;
        c.gpio.chip = g.required_text("chip");
        for (const char* k : {"estop_line", "enable_line", "sync_line"}) {
            if (!g.has(k)) g.fail(top.get("gpio"), k, "missing (required): line offset on the chip");
        }
        c.gpio.estop_line = static_cast<unsigned>(g.integer("estop_line", 0, 0, 1023));
        c.gpio.enable_line = static_cast<unsigned>(g.integer("enable_line", 0, 0, 1023));
        c.gpio.sync_line = static_cast<unsigned>(g.integer("sync_line", 0, 0, 1023));
        if (c.gpio.estop_line == c.gpio.enable_line || c.gpio.estop_line == c.gpio.sync_line || c.gpio.enable_line == c.gpio.sync_line)
            g.fail("sync_line", "estop_line, enable_line and sync_line must be different lines");
        c.gpio.estop_active_low = g.boolean("estop_active_low", c.gpio.estop_active_low);
        c.gpio.enable_active_low = g.boolean("enable_active_low", c.gpio.enable_active_low);
        g.reject_unknown();
    }

    top.mark_used("realtime");
    if (top.has("realtime")) {
        Section r(source, top.get("realtime"), "realtime");
        c.realtime.priority = static_cast<int>(r.integer("priority", c.realtime.priority, 0, 99));
        c.realtime.cpu = static_cast<int>(r.integer("cpu", c.realtime.cpu, -1, 1023));
        c.realtime.lock_memory = r.boolean("lock_memory", c.realtime.lock_memory);
        c.realtime.report_period = r.number("report_period", c.realtime.report_period, "s");
        // Each report is a write to stderr from the cycle loop: more than ten a second distorts the latency
        // it reports. Above 1e9 s its deadline in ns would overflow int64.
        const double period = c.realtime.report_period;
        if (period != 0.0 && !(period >= kMinReportPeriod && period <= kMaxSeconds)) {
            r.fail("report_period", fmt::format("{:g} s: expected 0 (only at exit) or a period in [{:g}, {:g}] s", period, kMinReportPeriod, kMaxSeconds));
        }
        r.reject_unknown();
    }
    top.mark_used("trajectory");
    if (top.has("trajectory")) {
        Section t(source, top.get("trajectory"), "trajectory");
        read_trajectory(t, top.get("trajectory"), c);
    }
    top.mark_used("monitor");
    if (top.has("monitor")) {
        Section m(source, top.get("monitor"), "monitor");
        read_monitor(m, c);
    }
    top.reject_unknown();
    // Before anything is opened for writing: no output over an input or over another output.
    const YAML::Node stream = top.get("stream"), trajectory = top.get("trajectory"), monitor = top.get("monitor");
    require_outputs_apart(source,
                          {{"this configuration file", source, YAML::Node()}, {"trajectory.file", c.trajectory.file, c.playback ? trajectory["file"] : YAML::Node()},
                           {"monitor.robot", c.monitor.robot, c.monitor.enabled ? monitor["robot"] : YAML::Node()},
                           {"monitor.thresholds", c.monitor.thresholds, c.monitor.enabled ? monitor["thresholds"] : YAML::Node()}},
                          {{"stream.log", c.stream.log, stream["log"]}, {"trajectory.log", c.trajectory.log, c.playback ? trajectory["log"] : YAML::Node()}});
    return c;
}

}  // namespace

FirmwareConfig parse_firmware_config(const std::string& yaml_text, const std::string& source) {
    const YAML::Node root = yaml::load<ConfigError>(yaml_text, source);
    if (!root.IsDefined() || root.IsNull()) throw ConfigError(fmt::format("{}: empty configuration", source));
    try {
        return read_config(root, source);
    } catch (const YAML::Exception& e) {
        // yaml-cpp throws where a node is not of the kind an accessor assumed. Every such case the fuzzer
        // found has its own message above (e.g. a list used as a key); this keeps any other a ConfigError.
        const std::string where = e.mark.is_null() ? source : fmt::format("{}:{}:{}", source, e.mark.line + 1, e.mark.column + 1);
        throw ConfigError(fmt::format("{}: unexpected YAML structure: {}", where, e.msg));
    }
}

FirmwareConfig load_firmware_config(const std::string& path) {
    return parse_firmware_config(yaml::read_input_file<ConfigError>(path, "the configuration file"), path);
}

}  // namespace jacobid::firmware
