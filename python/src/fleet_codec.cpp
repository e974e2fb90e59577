// SPDX-License-Identifier: MIT
#include "fleet_codec.hpp"

#include <fmt/core.h>

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"

// Every field of every struct below is listed: a field left out would be lost on the way to a worker (the
// equality of a fleet's result with the command line's, tests/python/test_fleet.py, would then fail).
namespace nlohmann {
// A matrix as its size, a bitmap of the entries that are not +0.0 (bit pattern zero) and those entries' raw doubles
// in column-major order: exact (-0.0, infinities and NaN are kept as they are), and a PUMA 560 factor travels as
// 0.7 MB instead of 2.3 MB (71 % of its lagged products' entries are zero: a joint's torque does not depend on
// the links before it, docs/fleet.md).
template <>
struct adl_serializer<Eigen::MatrixXd> {
    static void to_json(json& j, const Eigen::MatrixXd& m) {
        const auto n = static_cast<std::size_t>(m.size());
        std::vector<std::uint8_t> mask((n + 7) / 8, 0);
        std::vector<std::uint8_t> values;
        values.reserve(n * sizeof(double));
        for (std::size_t i = 0; i < n; ++i) {
            std::uint64_t bits = 0;
            std::memcpy(&bits, m.data() + i, sizeof bits);
            if (bits == 0) continue;
            mask[i / 8] = static_cast<std::uint8_t>(mask[i / 8] | (1U << (i % 8)));
            const auto* bytes = reinterpret_cast<const std::uint8_t*>(&bits);
            values.insert(values.end(), bytes, bytes + sizeof bits);
        }
        j = {{"rows", m.rows()}, {"cols", m.cols()}, {"nonzero", json::binary(std::move(mask))}, {"data", json::binary(std::move(values))}};
    }
    static void from_json(const json& j, Eigen::MatrixXd& m) {
        m.resize(j.at("rows").get<Eigen::Index>(), j.at("cols").get<Eigen::Index>());
        const auto n = static_cast<std::size_t>(m.size());
        const auto& mask = j.at("nonzero").get_binary();
        const auto& values = j.at("data").get_binary();
        if (mask.size() != (n + 7) / 8) throw jacobid::InputError("factor: a matrix of the wrong size");
        std::size_t k = 0;
        for (std::size_t i = 0; i < n; ++i) {
            std::uint64_t bits = 0;
            if ((mask[i / 8] >> (i % 8)) & 1U) {
                if ((k + 1) * sizeof bits > values.size()) throw jacobid::InputError("factor: a matrix of the wrong size");
                std::memcpy(&bits, values.data() + k * sizeof bits, sizeof bits);
                ++k;
            }
            std::memcpy(m.data() + i, &bits, sizeof bits);
        }
        if (k * sizeof(double) != values.size()) throw jacobid::InputError("factor: a matrix of the wrong size");
    }
};
}  // namespace nlohmann

namespace jacobid::identify {

NLOHMANN_JSON_SERIALIZE_ENUM(Method, {{Method::Jacobi, "jacobi"}, {Method::Butterworth, "butterworth"}})
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(JointBandwidth, name, frequency, energy_frequency, noise_limit, noise_rms, floor_fraction, quantization_step,
                                   jumps, moving, used)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(JointTorqueBandwidth, name, frequency, noise_rms, floor_fraction, moving, used)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TorqueBandwidth, frequency, resolution, highest, noise_known, joints)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(BandwidthEstimate, frequency, resolution, moving, energy_frequency, noise_limit, noise_limited, all_below_floor,
                                   jumps, joints, description, torque, differentiator_frequency, torque_wider, torque_noise_limited)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(PipelineInfo, method, sample_period, samples, bandwidth, bandwidth_estimated, bandwidth_estimate,
                                   differentiator_cutoff, velocity_window, acceleration_window, velocity_cutoff, acceleration_cutoff,
                                   prefilter_cutoff, coulomb_velocity_cutoffs, coulomb_velocity_ratios, decimation_cutoff, decimation, first,
                                   last, crop, seconds_differentiate, seconds_regressor_filter, seconds_ls, joint_range, joint_moves)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SegmentSource, option, noun)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TorqueDelayEstimate, delay, std_dev, compensated, at_bound, evaluations, samples_used, grid, rss)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TorqueDelayResult, given, estimate)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(JointSmoothing, chosen, reason, alpha, heldout_rms)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(CoulombSmoothingChoice, candidates, folds, passes, common_alpha, common_score, joints)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(JointShape, chosen, reason, index, heldout_rms)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ShapeChoice, folds, passes, common, common_score, joints)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(PreslidingDisplacementChoice, candidates, shape, displacement)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(JointFactors, r, rows, lagged)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(PlotRows, t, y, w)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(PipelineOutput, info, factors, plot)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SegmentedOutput, merged, used, why, rows, used_count)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SegmentReport, first_line, last_line, duration, samples, used, why, rows, log)

}  // namespace jacobid::identify

namespace jacobid::python {
namespace {

using nlohmann::json;

template <class T>
json optional_json(const std::optional<T>& v) {
    return v ? json(*v) : json(nullptr);
}

template <class T>
std::optional<T> optional_of(const json& j) {
    if (j.is_null()) return std::nullopt;
    return j.get<T>();
}

// The plan's `segments.fixed` is not carried: the receiver imposes `segments.info` on its own settings from the
// same options (identify::imposed_settings), as plan_segments did; only the Coulomb columns' velocity is added.
json method_json(const job::MethodPlan& p) {
    return {{"method", p.method},
            {"source", p.segments.source},
            {"reference", p.segments.reference},
            {"info", p.segments.info},
            {"coulomb_velocity_ratios", p.segments.fixed.coulomb_velocity_ratios},
            {"delay", p.delay},
            {"coulomb_smoothing", optional_json(p.smoothed.choice)},
            {"presliding", optional_json(p.smoothed.presliding)}};
}

json parse(const std::string& bytes, const char* what) {
    try {
        return json::from_cbor(bytes.begin(), bytes.end());
    } catch (const json::exception& e) {
        throw InputError(fmt::format("{}: not a jacobid {} ({})", what, what, e.what()));
    }
}

}  // namespace

std::string encode_plan(const std::vector<job::MethodPlan>& plan) {
    json j = json::array();
    for (const job::MethodPlan& p : plan) j.push_back(method_json(p));
    const std::vector<std::uint8_t> bytes = json::to_cbor(j);
    return {bytes.begin(), bytes.end()};
}

std::vector<job::MethodPlan> decode_plan(const std::string& bytes, const robot::RobotDescription& robot) {
    const json j = parse(bytes, "plan");
    std::vector<job::MethodPlan> plan;
    try {
        for (const json& m : j) {
            job::MethodPlan& p = plan.emplace_back();
            p.method = m.at("method").get<identify::Method>();
            p.segments.source = m.at("source").get<identify::SegmentSource>();
            p.segments.reference = m.at("reference").get<std::size_t>();
            p.segments.info = m.at("info").get<identify::PipelineInfo>();
            p.segments.fixed.coulomb_velocity_ratios = m.at("coulomb_velocity_ratios").get<std::vector<double>>();
            p.delay = m.at("delay").get<identify::TorqueDelayResult>();
            p.smoothed.choice = optional_of<identify::CoulombSmoothingChoice>(m.at("coulomb_smoothing"));
            p.smoothed.presliding = optional_of<identify::PreslidingDisplacementChoice>(m.at("presliding"));
            identify::make_chosen_model(robot, p.smoothed);
        }
    } catch (const json::exception& e) {
        throw InputError(fmt::format("plan: not a jacobid plan ({})", e.what()));
    }
    return plan;
}

std::string encode_factor(const FactorData& f) {
    const json j = {{"inputs", f.inputs}, {"pieces", f.pieces}, {"names", f.names}, {"methods", f.methods}, {"parse_seconds", f.parse_seconds}};
    const std::vector<std::uint8_t> bytes = json::to_cbor(j);
    return {bytes.begin(), bytes.end()};
}

FactorData decode_factor(const std::string& bytes) {
    const json j = parse(bytes, "factor");
    FactorData f;
    try {
        f.inputs = j.at("inputs").get<std::vector<std::string>>();
        f.pieces = j.at("pieces").get<std::vector<identify::SegmentReport>>();
        f.names = j.at("names").get<std::vector<std::string>>();
        f.methods = j.at("methods").get<std::vector<identify::SegmentedOutput>>();
        f.parse_seconds = j.at("parse_seconds").get<double>();
    } catch (const json::exception& e) {
        throw InputError(fmt::format("factor: not a jacobid factor ({})", e.what()));
    }
    return f;
}

}  // namespace jacobid::python
