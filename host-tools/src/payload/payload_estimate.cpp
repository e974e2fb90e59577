// SPDX-License-Identifier: MIT
#include "payload/payload_estimate.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "payload/payload_equations.hpp"
#include "payload/payload_uncertainty.hpp"

namespace jacobid::payload {
namespace {

constexpr int kM = 9;

// Moves parameter columns with known values to the right-hand side: rhs -= value * column, in every joint's
// factor and lagged products (a linear map T of each row, so R -> R T and Gamma -> T^T Gamma T).
void fix_columns(identify::JointFactors& f, const std::vector<std::pair<int, double>>& fixed) {
    if (fixed.empty()) return;
    const Eigen::Index n = f.r.front().cols();
    Eigen::MatrixXd t = Eigen::MatrixXd::Identity(n, n);
    for (const auto& [k, v] : fixed) t(k, n - 1) = -v;
    for (std::size_t j = 0; j < f.r.size(); ++j) {
        f.r[j] = f.r[j] * t;
        if (j < f.lagged.size()) {
            for (auto& g : f.lagged[j]) g = t.transpose() * g * t;
        }
    }
}

// The point-mass prior of parameter k given the mass m and first moments ms: inertia about the origin of a
// point mass (zero about its centre of mass); a first moment the rows miss: 0 (the centre of mass on the frame).
double point_mass_prior(int k, double m, const Eigen::Vector3d& ms) {
    if (k >= 6) return 0.0;
    const Eigen::Vector3d c = ms / m;
    const Eigen::Matrix3d i = m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    static const int rows[6] = {0, 0, 0, 1, 1, 2}, cols[6] = {0, 1, 2, 1, 2, 2};
    return i(rows[k], cols[k]);
}

identify::LsSolution solve(const identify::JointFactors& f, const std::vector<std::string>& names, const std::vector<bool>& free,
                           const identify::SolveOptions& base) {
    identify::SolveOptions o = base;
    o.active.assign(names.size(), false);
    for (int k = 0; k < 10; ++k) o.active[static_cast<std::size_t>(k)] = free[static_cast<std::size_t>(k)];
    return identify::solve_least_squares(f, names, o);
}

// The free fit's inertia when the rows do not determine it: about the centre of mass it describes no body
// (consistency_violations) and one of its six entries is not significant (std above half its magnitude), so
// that the inconsistency is noise, not a finding. Then the six inertias are better fixed to the point-mass prior
// than reported (the real UR10e pair: %sigma 60-210 %, negative principal moments; docs/real-data.md).
std::optional<Inertial> inertia_not_determined(const identify::LsSolution& sol, const std::vector<bool>& free) {
    for (int k = 0; k < 10; ++k) {
        if (!free[static_cast<std::size_t>(k)] || !sol.identified[static_cast<std::size_t>(k)]) return std::nullopt;
    }
    Standard10 x = sol.x.head<10>();
    const Inertial i = to_inertial(x, Eigen::Isometry3d::Identity());
    if (consistency_violations(i).empty()) return std::nullopt;
    Matrix10 cov = sol.covariance.topLeftCorner<10, 10>();
    const Eigen::Matrix<double, 10, 10> jac = inertial_jacobian(x, Eigen::Isometry3d::Identity());
    const Inertial10 sd = (jac * cov * jac.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
    for (int k = 4; k < 10; ++k) {
        if (sd[k] > 0.5 * std::abs(flatten(i)[k])) return i;
    }
    return std::nullopt;
}

Inertial10 std_of(const Eigen::Matrix<double, 10, 10>& jac, const Matrix10& cov) {
    return (jac * cov * jac.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
}

// The estimate in the tool frame with its std (noise, arm, gains, total), the physical-consistency check, and
// the warnings: what the motion does not determine, a poorly determined mass, runs that are not one trajectory.
void describe_estimate(PayloadEstimate& out, const PayloadSettings& settings) {
    out.inertial = to_inertial(out.standard, settings.tool);
    const Eigen::Matrix<double, 10, 10> jac = inertial_jacobian(out.standard, settings.tool);
    out.std_noise = std_of(jac, out.cov_noise);
    out.std_arm = std_of(jac, out.cov_arm);
    out.std_gain = std_of(jac, out.cov_gain);
    out.std_total = std_of(jac, out.covariance());
    const bool inertia_prior = std::any_of(out.status, out.status + 6, [](Status st) { return st == Status::Prior; });
    if (inertia_prior) {
        // A point mass has no inertia about its centre: the prior is not checked as a body, and its entries have no
        // measured std (what the delta method gives is the centre of mass's, moved into them).
        if (std::all_of(out.status, out.status + 6, [](Status st) { return st == Status::Prior; })) out.inertial.inertia.setZero();  // not rounding
        for (int k = 4; k < 10; ++k) out.std_noise[k] = out.std_arm[k] = out.std_gain[k] = out.std_total[k] = std::nan("");
        if (!(out.inertial.mass > 0.0)) out.violations.push_back(fmt::format("mass {:.4g} kg is not positive", out.inertial.mass));
    } else {
        out.violations = consistency_violations(out.inertial);
    }
    if (out.inertia_free_fit) {
        const auto& i = out.inertia_free_fit->inertia;
        out.warnings.push_back(fmt::format("the motion does not determine the inertia (free fit about the centre of mass: XX {:.3g} XY {:.3g} XZ {:.3g} "
                                           "YY {:.3g} YZ {:.3g} ZZ {:.3g} kg.m^2, no body has it, and not significant): the six inertias are fixed "
                                           "to the point-mass prior (zero about the centre of mass), mass and centre of mass solved again",
                                           i[0], i[1], i[2], i[3], i[4], i[5]));
    }
    for (int k = 0; k < 10; ++k) {
        if (out.status[k] == Status::Prior && !out.inertia_free_fit) {
            out.warnings.push_back(fmt::format("{}: not determined by the motion; fixed to the point-mass prior ({:.4g})", standard_names()[static_cast<std::size_t>(k)],
                                               out.standard[k]));
        }
    }
    if (!out.violations.empty()) out.warnings.push_back("physically inconsistent: " + out.violations.front());
    const double rel_mass = 100.0 * out.std_total[0] / std::abs(out.inertial.mass);
    if (!settings.mass && rel_mass > 10.0) out.warnings.push_back(fmt::format("the mass is poorly determined (%sigma {:.1f})", rel_mass));
    // A tenth of the motion: beyond the tracking error a load changes, the runs do not follow one trajectory.
    if (out.alignment && out.alignment->position_rms > 0.1 * out.alignment->motion_rms) {
        out.warnings.push_back(fmt::format("the runs' positions differ by {:.3g} rad RMS after the time shift, against a motion of {:.3g} rad RMS: "
                                           "the same trajectory?",
                                           out.alignment->position_rms, out.alignment->motion_rms));
    }
}

}  // namespace

const char* to_string(Status s) {
    switch (s) {
        case Status::Identified: return "identified";
        case Status::Known: return "known";
        case Status::Prior: return "prior";
    }
    return "?";
}

PayloadEstimate estimate_payload(const ArmModel& arm, const identify::LogColumns& loaded, const identify::LogColumns* unloaded,
                                 const PayloadSettings& settings) {
    const robot::RobotModel& model = *arm.model;
    const int joints = model.joint_count();
    if (static_cast<int>(loaded.q.size()) != joints) {
        throw InputError(fmt::format("--in {}: {} joints, but the arm of --arm {} has {}", loaded.source, loaded.q.size(), arm.source, joints));
    }
    if (!settings.gain_std.empty() && static_cast<int>(settings.gain_std.size()) != joints) {
        throw InputError(fmt::format("--gain-std: {} values given, expected one per joint ({})", settings.gain_std.size(), joints));
    }
    PayloadEstimate out;
    out.loaded_source = loaded.source;
    out.arm_source = arm.source;
    out.frame_name = settings.frame_name;
    out.tool = settings.tool;
    const identify::IdentifySettings& s = settings.identify;

    PayloadEquations eq = payload_equations(arm, loaded, unloaded, s);
    out.delay = eq.delay;
    out.delay_from_arm = eq.delay_from_arm;
    out.alignment = eq.alignment;
    out.info = eq.info;
    if (unloaded) out.unloaded_source = unloaded->source;
    const identify::JointFactors& factors = eq.factors;
    const std::vector<std::string>& names = eq.names;
    const std::string& rows_source = eq.source;

    std::vector<bool> free(10, true);
    std::vector<std::pair<int, double>> fixed;
    for (auto& st : out.status) st = Status::Identified;
    if (settings.mass) {
        free[kM] = false;
        out.status[kM] = Status::Known;
        fixed.push_back({kM, *settings.mass});
    }
    identify::JointFactors solved = factors;
    fix_columns(solved, fixed);
    out.solution = solve(solved, names, free, s.solve);
    out.unidentifiable = out.solution.unidentifiable;
    std::vector<int> missing;
    for (int k = 0; k < 10; ++k) {
        if (free[static_cast<std::size_t>(k)] && !out.solution.identified[static_cast<std::size_t>(k)]) missing.push_back(k);
    }
    auto fix_to_prior = [&](const std::vector<int>& ks) {
        const double m = settings.mass ? *settings.mass : out.solution.x[kM];
        if (!(std::isfinite(m) && m > 0.0)) {
            throw InputError(fmt::format("payload: the mass is not identifiable from {} (rank {} of {}): does the motion load the joints with the "
                                         "payload's weight? Give --mass KG",
                                         rows_source, out.solution.rank, 10 - static_cast<int>(fixed.size())));
        }
        Eigen::Vector3d ms;
        for (int a = 0; a < 3; ++a) ms[a] = out.solution.identified[static_cast<std::size_t>(6 + a)] ? out.solution.x[6 + a] : 0.0;
        for (int k : ks) {
            free[static_cast<std::size_t>(k)] = false;
            out.status[k] = Status::Prior;
            fixed.push_back({k, point_mass_prior(k, m, ms)});
        }
        // The prior depends on the mass and centre of mass it is solved with: a few fixed-point passes (each
        // moves them by the prior's small share of the torque; 3 settle them to rounding on the UR10e pair).
        for (int pass = 0; pass < 3; ++pass) {
            solved = factors;
            fix_columns(solved, fixed);
            out.solution = solve(solved, names, free, s.solve);
            const double mm = settings.mass ? *settings.mass : out.solution.x[kM];
            Eigen::Vector3d mc;
            for (int a = 0; a < 3; ++a) mc[a] = free[static_cast<std::size_t>(6 + a)] ? out.solution.x[6 + a] : 0.0;
            if (!(std::isfinite(mm) && mm > 0.0)) break;
            for (auto& [k, v] : fixed) {
                if (out.status[k] == Status::Prior) v = point_mass_prior(k, mm, mc);
            }
        }
    };
    if (!missing.empty()) fix_to_prior(missing);
    out.inertia_free_fit = inertia_not_determined(out.solution, free);
    if (out.inertia_free_fit) fix_to_prior({0, 1, 2, 3, 4, 5});
    identify::require_finite_solution(out.solution, rows_source);
    for (const auto& [k, v] : fixed) out.standard[k] = v;
    std::vector<int> f;  // the free payload parameters
    for (int k = 0; k < 10; ++k) {
        if (!free[static_cast<std::size_t>(k)]) continue;
        out.standard[k] = out.solution.x[k];
        f.push_back(k);
    }
    const auto nf = static_cast<Eigen::Index>(f.size());
    out.included.push_back(fmt::format("measurement noise ({} std of identify's least squares)", identify::to_string(out.solution.std_method)));
    for (Eigen::Index a = 0; a < nf; ++a) {
        for (Eigen::Index b = 0; b < nf; ++b) out.cov_noise(f[a], f[b]) = out.solution.covariance(f[a], f[b]);
    }

    add_inherited_uncertainty(out, solved, f, arm, unloaded != nullptr, settings.gain_std);

    describe_estimate(out, settings);
    return out;
}

}  // namespace jacobid::payload
