// SPDX-License-Identifier: MIT
#include "jacobid/firmware/firmware_config_yaml.hpp"

#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <memory>
#include <sstream>

#include "jacobid/differentiator_bank.hpp"
#include "jacobid/yaml/yaml_section.hpp"

namespace jacobid::firmware {
namespace {

using Section = yaml::YamlSection<ConfigError>;

// The joint key a HAL config status is about, so the error points at the right line.
const char* key_of(hal::ConfigStatus s, ProfileKind kind) {
    switch (s) {
        case hal::ConfigStatus::InvalidGearRatio: return "gear_ratio";
        case hal::ConfigStatus::InvalidDirection: return "direction";
        case hal::ConfigStatus::InvalidTorqueConstant: return "torque_constant";
        case hal::ConfigStatus::InvalidLimits: return "max_torque";
        case hal::ConfigStatus::InvalidRange: return "effort_range";
        case hal::ConfigStatus::InvalidCanId: return kind == ProfileKind::Mit ? "reply_id" : "cob_id";
        case hal::ConfigStatus::InvalidNodeId: return "node_id";
        case hal::ConfigStatus::InvalidScale: return kind == ProfileKind::Cia402 ? "counts_per_rev" : "position_wrap_turns";
        case hal::ConfigStatus::InvalidLayout: return "effort_byte";
        default: return "profile";
    }
}

hal::JointMapping read_mapping(Section& s, hal::JointMapping m) {
    m.gear_ratio = s.number("gear_ratio", m.gear_ratio);
    m.direction = s.number("direction", m.direction);
    if (m.direction != 1.0 && m.direction != -1.0) s.fail("direction", "must be 1 or -1");
    m.position_offset = s.number("offset", m.position_offset);
    m.torque_constant = s.number("torque_constant", m.torque_constant);
    m.max_abs_velocity = s.positive("max_velocity", m.max_abs_velocity);
    m.max_abs_torque = s.positive("max_torque", m.max_abs_torque);
    return m;
}

JointConfig read_joint(const std::string& source, const YAML::Node& node, std::size_t index) {
    Section s(source, node, fmt::format("joints[{}]", index));
    JointConfig j;
    j.name = s.text("name", fmt::format("j{}", index + 1));
    if (!s.has("profile")) s.fail(node, "profile", "missing (required): mit, cia402 or odrive");
    const std::string profile = s.choice("profile", "", {"mit", "cia402", "odrive"});
    j.profile = profile == "mit" ? ProfileKind::Mit : profile == "cia402" ? ProfileKind::Cia402 : ProfileKind::Odrive;
    hal::ProfileConfig decoder = default_profile_config(j.profile, index);
    if (auto* m = std::get_if<hal::mit::JointConfig>(&decoder)) {
        m->reply_can_id = static_cast<std::uint32_t>(s.integer("reply_id", static_cast<long>(m->reply_can_id), 0, hal::kCanExtendedIdMask));
        m->extended_id = s.boolean("extended_id", m->extended_id);
        m->motor_id = static_cast<std::uint8_t>(s.integer("motor_id", m->motor_id, 0, 255));
        const auto p = s.range("position_range", {m->ranges.p_min, m->ranges.p_max});
        const auto v = s.range("velocity_range", {m->ranges.v_min, m->ranges.v_max});
        const auto t = s.range("effort_range", {m->ranges.t_min, m->ranges.t_max});
        m->ranges = {p.first, p.second, v.first, v.second, t.first, t.second};
        m->effort = s.choice("effort", "torque", {"torque", "current"}) == "current" ? hal::EffortKind::Current : hal::EffortKind::Torque;
        m->require_status = s.boolean("require_status", m->require_status);
        m->mapping = read_mapping(s, m->mapping);
    } else if (auto* c = std::get_if<hal::cia402::JointConfig>(&decoder)) {
        c->node_id = static_cast<std::uint8_t>(s.integer("node_id", c->node_id, 1, 127));
        c->layout.cob_id = static_cast<std::uint32_t>(s.integer("cob_id", 0, 0, hal::kCanStandardIdMask));
        c->counts_per_revolution = s.positive("counts_per_rev", c->counts_per_revolution);
        const std::string effort = s.choice("effort", "torque", {"torque", "current", "none"});
        c->layout.effort = effort == "torque"    ? hal::cia402::EffortObject::TorqueActual
                           : effort == "current" ? hal::cia402::EffortObject::CurrentActual
                                                 : hal::cia402::EffortObject::None;
        c->rated_torque = s.number("rated_torque", c->rated_torque);
        c->rated_current = s.number("rated_current", c->rated_current);
        c->layout.position_byte = static_cast<std::uint8_t>(s.integer("position_byte", c->layout.position_byte, 0, 4));
        c->layout.effort_byte = static_cast<std::uint8_t>(s.integer("effort_byte", c->layout.effort_byte, 0, 6));
        c->mapping = read_mapping(s, c->mapping);
        if (c->layout.effort == hal::cia402::EffortObject::CurrentActual && !(c->rated_current > 0.0))
            s.fail(node, "rated_current", "required (> 0 A) with effort: current");
        if (c->layout.effort == hal::cia402::EffortObject::TorqueActual && !(c->rated_torque > 0.0))
            s.fail("rated_torque", "must be > 0 N.m with effort: torque");
        if (c->layout.effort == hal::cia402::EffortObject::CurrentActual && !s.has("torque_constant"))
            s.fail(node, "torque_constant", "required (N.m/A) with effort: current");
    } else if (auto* o = std::get_if<hal::odrive::JointConfig>(&decoder)) {
        o->node_id = static_cast<std::uint8_t>(s.integer("node_id", o->node_id, 0, hal::odrive::kMaxNodeId));
        o->position_wrap_turns = s.number("position_wrap_turns", o->position_wrap_turns);
        o->mapping = read_mapping(s, o->mapping);
    }
    s.reject_unknown();
    // The HAL's own validation, reported at the key it is about.
    hal::ConfigStatus st = hal::ConfigStatus::Ok;
    if (const auto* m = std::get_if<hal::mit::JointConfig>(&decoder)) st = hal::mit::validate(*m);
    if (const auto* c = std::get_if<hal::cia402::JointConfig>(&decoder)) st = hal::cia402::validate(*c);
    if (const auto* o = std::get_if<hal::odrive::JointConfig>(&decoder)) st = hal::odrive::validate(*o);
    if (st != hal::ConfigStatus::Ok) s.fail(key_of(st, j.profile), hal::describe(st));
    j.decoder = decoder;
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

FirmwareConfig read_config(const YAML::Node& root, const std::string& source) {
    FirmwareConfig c;
    c.source = source;
    Section top(source, root, "");
    c.rate = top.positive("rate", c.rate);
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
    c.stream.log = st.text("log", "");
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
        c.realtime.report_period = r.number("report_period", c.realtime.report_period);
        if (c.realtime.report_period < 0.0) r.fail("report_period", "must be >= 0 s (0: only at exit)");
        r.reject_unknown();
    }
    top.reject_unknown();
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
    std::ifstream in(path);
    if (!in) throw ConfigError(fmt::format("{}: cannot open the configuration file", path));
    std::stringstream text;
    text << in.rdbuf();
    return parse_firmware_config(text.str(), path);
}

}  // namespace jacobid::firmware
