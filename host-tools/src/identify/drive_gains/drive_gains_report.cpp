// SPDX-License-Identifier: MIT
#include "identify/drive_gains/drive_gains_report.hpp"

#include <fmt/core.h>

#include <cmath>

namespace jacobid::identify {
namespace {

std::vector<const DriveGainEstimate*> estimates(const DriveGainResult& r) {
    std::vector<const DriveGainEstimate*> e{&r.least_squares, &r.tls};
    if (r.constrained) e.push_back(&*r.constrained);
    return e;
}

nlohmann::json payload_json(const Eigen::Matrix<double, 10, 1>& payload) {
    nlohmann::json j = nlohmann::json::object();
    for (int k = 0; k < 10; ++k) j[payload_names()[static_cast<std::size_t>(k)]] = std::isfinite(payload[k]) ? nlohmann::json(payload[k]) : nlohmann::json();
    return j;
}

std::vector<double> to_vector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

// A gain in the text table: an estimator that gave none (TLS on a degenerate system, no constrained fit)
// shows "-", never nan or inf.
std::string gain_cell(double value, int width) {
    return std::isfinite(value) ? fmt::format("{:>{}.5g}", value, width) : fmt::format("{:>{}}", "-", width);
}

}  // namespace

Eigen::VectorXd absolute_gains(const DriveGainResult& result, const DriveGainEstimate& estimate) {
    Eigen::VectorXd g = estimate.gains;
    for (Eigen::Index j = 0; j < g.size(); ++j) g[j] *= result.prior_gains[static_cast<std::size_t>(j)];
    return g;
}

std::string gains_line(const Eigen::VectorXd& gains) {
    std::string line = "gains: [";
    for (Eigen::Index j = 0; j < gains.size(); ++j) line += fmt::format("{}{:.6g}", j ? ", " : "", gains[j]);
    return line + "]";
}

std::string drive_gains_text(const DriveGainResult& r, const ReportContext& context) {
    std::string t = format_table({r.method}, context);
    const LsSolution& s = r.method.solution;
    t += fmt::format("\nDrive gains (current to torque) from {} (unloaded, {} equations) and {} (loaded, {} equations), payload {} kg; "
                     "rank {} of {} columns ({} payload parameters unknown)\n",
                     r.unloaded_source, r.unloaded_equations, r.loaded_source, r.loaded_equations, r.payload.known[9], s.rank,
                     s.names.size(), r.payload_columns);
    t += fmt::format("{:<20} {:>10} {:>10} {:>10} {:>12} {:>10} {:>12}\n", "joint", r.least_squares.estimator, "std", "tls", "constrained", "prior",
                     "payload %");
    const Eigen::VectorXd ls = absolute_gains(r, r.least_squares), tls = absolute_gains(r, r.tls);
    const Eigen::VectorXd con = r.constrained ? absolute_gains(r, *r.constrained) : Eigen::VectorXd::Constant(r.joints, std::nan(""));
    for (int j = 0; j < r.joints; ++j) {
        const std::string name = j < static_cast<int>(context.joint_names.size()) ? context.joint_names[static_cast<std::size_t>(j)] : fmt::format("{}", j + 1);
        const double prior = r.prior_gains[static_cast<std::size_t>(j)];
        t += fmt::format("{:<20} {:>10.5g} {:>10.3g} {} {} {:>10.5g} {:>12.3g}\n", name, ls[j], r.least_squares.std_dev[j] * prior, gain_cell(tls[j], 10),
                         gain_cell(con[j], 12), prior, 100.0 * r.payload_share[static_cast<std::size_t>(j)]);
    }
    if (r.constrained) t += fmt::format("constrained: {}\n", r.constrained->note);
    t += fmt::format("for a log-format file ({}): {}\n", r.least_squares.estimator, gains_line(ls));
    return t;
}

nlohmann::json drive_gains_json(const DriveGainResult& r, const ReportContext& context) {
    nlohmann::json j = to_json(r.method, context);
    nlohmann::json d;
    d["unloaded"] = {{"log", r.unloaded_source}, {"equations", r.unloaded_equations}};
    d["loaded"] = {{"log", r.loaded_source}, {"equations", r.loaded_equations}};
    d["payload_mass"] = r.payload.known[9];
    std::vector<std::string> unknown;
    for (int k : r.payload.unknown) unknown.push_back(payload_names()[static_cast<std::size_t>(k)]);
    d["payload_unknown"] = unknown;
    d["rank"] = r.method.solution.rank;
    d["columns"] = r.method.solution.names.size();
    d["prior_gains"] = r.prior_gains;
    d["estimator"] = r.least_squares.estimator;
    const Eigen::VectorXd ls = absolute_gains(r, r.least_squares);
    nlohmann::json joints = nlohmann::json::array();
    for (int k = 0; k < r.joints; ++k) {
        nlohmann::json row = {{"joint", k < static_cast<int>(context.joint_names.size()) ? context.joint_names[static_cast<std::size_t>(k)] : ""},
                              {"gain", ls[k]},
                              {"std", r.least_squares.std_dev[k] * r.prior_gains[static_cast<std::size_t>(k)]},
                              {"prior", r.prior_gains[static_cast<std::size_t>(k)]},
                              {"payload_share", r.payload_share[static_cast<std::size_t>(k)]}};
        for (const DriveGainEstimate* e : estimates(r)) row[e->estimator] = absolute_gains(r, *e)[k];
        joints.push_back(row);
    }
    d["joints"] = joints;
    for (const DriveGainEstimate* e : estimates(r)) {
        nlohmann::json est = {{"gains", to_vector(absolute_gains(r, *e))}, {"payload", payload_json(e->payload)}, {"converged", e->converged}};
        if (e == &r.least_squares) est["std"] = to_vector(r.least_squares.std_dev.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(r.prior_gains.data(), r.joints)));
        if (!e->note.empty()) est["note"] = e->note;
        d["estimators"][e->estimator] = est;
    }
    d["gains_line"] = gains_line(ls);
    j["drive_gains"] = d;
    return j;
}

}  // namespace jacobid::identify
