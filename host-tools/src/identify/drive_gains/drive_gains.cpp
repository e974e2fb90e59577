// SPDX-License-Identifier: MIT
#include "identify/drive_gains/drive_gains.hpp"

#include <fmt/core.h>

#include <cmath>
#include <stdexcept>

#include "core/errors.hpp"
#include "identify/friction/coulomb_smoothing.hpp"
#include "identify/drive_gains/drive_gains_constrained.hpp"
#include "identify/drive_gains/drive_gains_tls.hpp"
#include "identify/pipeline/merge_factors.hpp"
#include "identify/physical/plausibility.hpp"
#include "identify/solve/residual_correlation.hpp"
#include "identify/pipeline/running_qr.hpp"
#include "identify/friction/torque_delay.hpp"
#include "identify/validation/validation.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::identify {
namespace {

constexpr const char* kTenKinds[10] = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"};

// Every decimated row of one log as joint-wise equations over [theta; phi_u; g | rhs] (drive_gains.hpp),
// folded into per-joint factors and residual lag products as the pipeline folds its own rows.
class StackedRows final : public RowSink {
public:
    // payload_columns: c x p, the base-parameter effect of each unknown payload parameter (zero columns for
    // the unloaded log); known_effect: c, that of the known ones (zero for the unloaded log).
    StackedRows(int joints, const Eigen::MatrixXd& payload_columns, const Eigen::VectorXd& known_effect, int lags)
        : joints_(joints), payload_columns_(payload_columns), known_effect_(known_effect) {
        const int c = static_cast<int>(payload_columns.rows());
        width_ = c + static_cast<int>(payload_columns.cols()) + joints + 1;
        for (int j = 0; j < joints; ++j) {
            qr_.emplace_back(width_);
            lagged_.emplace_back(width_, lags);
        }
        row_.resize(width_);
    }

    void row(const DecimatedRow& r) override {
        const Eigen::Index c = payload_columns_.rows(), p = payload_columns_.cols();
        for (int j = 0; j < joints_; ++j) {
            row_.setZero();
            row_.head(c) = r.w.row(j).transpose();
            row_.segment(c, p) = payload_columns_.transpose() * r.w.row(j).transpose();
            row_[c + p + j] = -r.y[j];
            row_[width_ - 1] = -r.w.row(j).dot(known_effect_);
            qr_[static_cast<std::size_t>(j)].add_row(row_.data());
            lagged_[static_cast<std::size_t>(j)].add_row(row_.data());
        }
    }

    JointFactors factors() {
        JointFactors f;
        for (std::size_t j = 0; j < qr_.size(); ++j) {
            f.r.push_back(qr_[j].r());
            f.rows.push_back(qr_[j].rows());
            f.lagged.push_back(lagged_[j].gamma());
        }
        return f;
    }

private:
    int joints_, width_ = 0;
    Eigen::MatrixXd payload_columns_;
    Eigen::VectorXd known_effect_;
    std::vector<RunningQr> qr_;
    std::vector<LaggedProducts> lagged_;
    Eigen::VectorXd row_;
};

// How much of each joint's loaded torque the payload makes, ||W_j K_L phi|| / ||g_j y_j|| with phi the known
// and the identified payload parameters (norms through the loaded log's factors over [theta; phi_u; g | rhs]:
// R^T R = A^T A); a joint the payload hardly loads has a gain that only the other joints' equations tell.
std::vector<double> payload_shares(const JointFactors& loaded, const LsSolution& s, int c, int p, const Eigen::VectorXd& gains) {
    const auto joints = static_cast<int>(gains.size());
    Eigen::VectorXd effect = Eigen::VectorXd::Zero(c + p + joints + 1);
    effect.segment(c, p) = s.x.segment(c, p).unaryExpr([](double v) { return std::isnan(v) ? 0.0 : v; });
    effect[c + p + joints] = -1.0;
    std::vector<double> shares;
    for (int j = 0; j < joints; ++j) {
        const Eigen::MatrixXd& f = loaded.r[static_cast<std::size_t>(j)];
        const double torque = std::abs(gains[j]) * f.col(c + p + j).norm();
        shares.push_back(torque > 0.0 ? (f * effect).norm() / torque : 0.0);
    }
    return shares;
}

}  // namespace

const std::vector<std::string>& payload_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const char* k : kTenKinds) n.push_back(std::string(k) + "L");
        return n;
    }();
    return names;
}

PayloadParameters payload_parameters(const PayloadKnowledge& payload) {
    if (!(payload.mass > 0.0) || !std::isfinite(payload.mass)) {
        throw InputError(fmt::format("--payload-mass {}: expected the payload's mass in kg, > 0", payload.mass));
    }
    if (payload.inertia && !payload.com) {
        throw InputError("--payload-inertia needs --payload-com: an inertia about the centre of mass moves to the link frame only with it");
    }
    PayloadParameters p;
    const double m = payload.mass;
    p.known[9] = m;
    if (payload.com) p.known.segment<3>(6) = m * *payload.com;
    if (payload.inertia) {
        // I_O = I_c + m (|c|^2 E - c c^T) (parallel axes), stored as XX XY XZ YY YZ ZZ.
        const Eigen::Vector3d c = *payload.com;
        const auto& i = *payload.inertia;
        Eigen::Matrix3d ic;
        ic << i[0], i[1], i[2], i[1], i[3], i[4], i[2], i[4], i[5];
        const Eigen::Matrix3d io = ic + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
        p.known.head<6>() << io(0, 0), io(0, 1), io(0, 2), io(1, 1), io(1, 2), io(2, 2);
    }
    for (int k = 0; k < 9; ++k) {
        const bool first_moment = k >= 6;
        if (first_moment ? !payload.com : !payload.inertia) p.unknown.push_back(k);
    }
    return p;
}

std::vector<int> last_link_columns(const robot::SerialRobotModel& model) {
    const int last = model.joint_count();
    std::vector<int> columns;
    for (const char* k : kTenKinds) {
        const int index = model.standard_index(fmt::format("{}{}", k, last));
        if (index < 0) throw InputError(fmt::format("--drive-gains: the model has no standard parameter {}{}", k, last));
        columns.push_back(index);
    }
    return columns;
}

DriveGainResult identify_drive_gains(const robot::RobotDescription& description, const robot::RobotModel& nominal, const LogColumns& unloaded,
                                     const LogColumns& loaded, const IdentifySettings& settings, const PayloadKnowledge& payload) {
    DriveGainResult out;
    out.payload = payload_parameters(payload);
    if (unloaded.q.size() != loaded.q.size()) {
        throw InputError(fmt::format("--loaded {}: {} joints, but --in {} has {}", loaded.source, loaded.q.size(), unloaded.source, unloaded.q.size()));
    }
    out.unloaded_source = unloaded.source;
    out.loaded_source = loaded.source;
    // The unloaded log decides every automatic choice; the loaded one is read with the same filters.
    TorqueDelayResult delay = resolve_torque_delay(nominal, unloaded, settings.pipeline, settings.solve, settings.torque_delay);
    const ShiftedTorques aligned_unloaded = shift_torques(unloaded, delay.applied());
    const ShiftedTorques aligned_loaded = shift_torques(loaded, delay.applied());
    SmoothedModel smoothed = resolve_coulomb_smoothing(description, nominal, aligned_unloaded.log, settings.pipeline, settings.solve.weighted);
    const robot::RobotModel& fitted = smoothed.get(nominal);
    const auto* serial = dynamic_cast<const robot::SerialRobotModel*>(&fitted);
    if (!serial) {
        throw InputError(fmt::format("--drive-gains: model {} has no per-link standard parameters to carry the payload; describe the robot with "
                                     "model mdh or urdf (and no presliding friction)",
                                     fitted.model_name()));
    }
    const int joints = fitted.joint_count();
    const int c = fitted.parameter_count();
    const std::vector<int> link = last_link_columns(*serial);
    const Eigen::MatrixXd& regrouping = serial->base().regrouping;
    Eigen::MatrixXd payload_columns(c, static_cast<Eigen::Index>(out.payload.unknown.size()));
    for (std::size_t k = 0; k < out.payload.unknown.size(); ++k) {
        payload_columns.col(static_cast<Eigen::Index>(k)) = regrouping.col(link[static_cast<std::size_t>(out.payload.unknown[k])]);
    }
    Eigen::VectorXd known_effect = Eigen::VectorXd::Zero(c);
    for (int k = 0; k < 10; ++k) known_effect += regrouping.col(link[static_cast<std::size_t>(k)]) * out.payload.known[k];
    const int p = static_cast<int>(payload_columns.cols());

    StackedRows unloaded_rows(joints, Eigen::MatrixXd::Zero(c, p), Eigen::VectorXd::Zero(c), settings.pipeline.residual_lags);
    PipelineOutput first = run_pipeline(fitted, aligned_unloaded.log, settings.pipeline, &unloaded_rows);
    PipelineSettings same = validation_settings(settings.pipeline, first.info);
    same.decimation = first.info.decimation;
    StackedRows loaded_rows(joints, payload_columns, known_effect, settings.pipeline.residual_lags);
    const PipelineOutput second = run_pipeline(fitted, aligned_loaded.log, same, &loaded_rows);

    JointFactors factors = unloaded_rows.factors();
    const JointFactors loaded_factors = loaded_rows.factors();
    merge_factors(factors, loaded_factors);
    for (std::size_t j = 0; j < factors.rows.size(); ++j) {
        out.unloaded_equations += first.factors.rows[j];
        out.loaded_equations += second.factors.rows[j];
    }

    std::vector<std::string> names = fitted.parameter_names();
    for (int k : out.payload.unknown) names.push_back(payload_names()[static_cast<std::size_t>(k)]);
    for (int j = 0; j < joints; ++j) names.push_back(fmt::format("G{}", j + 1));

    MethodResult& r = out.method;
    r.torque_delay = std::move(delay);
    r.coulomb_smoothing = smoothed.choice;
    r.info = std::move(first.info);
    r.solution = solve_least_squares(factors, names, settings.solve);
    for (int j = 0; j < joints; ++j) {
        if (!r.solution.identified[static_cast<std::size_t>(c + p + j)]) {
            throw InputError(fmt::format("--drive-gains: the gain of joint {} is not identifiable from {} and {} (rank {} of {} columns): does "
                                         "the joint move, and does the payload load it?",
                                         j + 1, unloaded.source, loaded.source, r.solution.rank, names.size()));
        }
    }
    // The base parameters come first: their indices are the model's.
    r.violations = plausibility_violations(sign_constraints(fitted), r.solution);

    out.parameter_count = c;
    out.payload_columns = p;
    out.joints = joints;
    out.prior_gains.assign(static_cast<std::size_t>(joints), 1.0);
    out.factors = std::move(factors);
    out.least_squares.estimator = r.solution.weighted ? "wls" : "ols";
    out.least_squares.gains = r.solution.x.segment(c + p, joints);
    out.least_squares.std_dev = r.solution.std_dev.segment(c + p, joints);
    out.least_squares.payload = out.payload.known;
    for (int k = 0; k < p; ++k) out.least_squares.payload[out.payload.unknown[static_cast<std::size_t>(k)]] = r.solution.x[c + k];
    out.payload_share = payload_shares(loaded_factors, r.solution, c, p, out.least_squares.gains);
    out.tls = drive_gains_tls(out);
    try {
        out.constrained = drive_gains_constrained(out, *serial, description);
    } catch (const std::invalid_argument& e) {
        // A start outside the constraints: a given payload inertia that no body has.
        throw InputError(fmt::format("--drive-gains: the constrained estimate cannot start: {} (check --payload-com / --payload-inertia)", e.what()));
    }
    return out;
}

}  // namespace jacobid::identify
