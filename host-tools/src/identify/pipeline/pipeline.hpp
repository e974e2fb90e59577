// SPDX-License-Identifier: MIT
#pragma once
// The identification pipeline of the paper (Sec. II-B; docs/method.md, "Identification" and "Pitfalls") on one log:
//   1. joint velocities and accelerations from the measured positions: central Jacobi differentiators
//      whose windows are designed from a wanted cutoff (window_for_cutoff), or the Butterworth baseline
//      (forward-backward Butterworth on q and tau, then central Euler differences);
//   2. the regressor W row by row;
//   3. parallel decimation: Y and every column of W through the same zero-phase low-pass F_p, then every
//      d-th sample; the samples within h of the ends (invalid derivatives) are cropped BEFORE F_p and F_p's
//      own end transients after it;
//   4. rows folded into per-joint running QR factors (memory independent of the log length).
// F_p runs chunk by chunk with overlapping margins long enough for its impulse response to die out
// (to ~1e-20), so the whole W is never held in memory and the result equals a whole-record filtfilt.
// Cutoffs default to multiples of the motion bandwidth estimated from the data (bandwidth.hpp): the
// differentiators (or F_q) at 10x, F_p at 5x (the paper's rules of thumb, F_p below the differentiators).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "identify/plan/bandwidth.hpp"
#include "identify/solve/least_squares.hpp"
#include "identify/solve/residual_correlation.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::identify {

enum class Method { Jacobi, Butterworth };
const char* to_string(Method m);

// Auto Coulomb velocity: largest s'_j(0) sigma_v,j, the velocity noise against the transition width of joint j's
// sign function s_j (s'(0) = 2 alpha / pi for the smoothed atan sign). Measured on issue 14's 2R (alpha 100,
// 65536 counts): 0.052 (2 x the cutoff) unbiased, 0.098 (3 x) FV2 -0.24 %, 0.18 (alpha 1000, 1 x) FC2 +0.2 %;
// the budget is the midpoint between the unbiased and the biased case.
inline constexpr double kCoulombVelocityNoise = 0.07;

struct PipelineSettings {
    Method method = Method::Jacobi;
    double bandwidth = 0.0;              // Hz; 0: estimated (bandwidth.hpp: energy above the noise floor, limited by the noise)
    double differentiator_ratio = 10.0;  // differentiator / F_q cutoff = ratio x bandwidth
    double decimation_ratio = 5.0;       // F_p cutoff = ratio x bandwidth
    double differentiator_cutoff = 0.0;  // Hz; overrides the ratio
    // Hz: the differentiators of a validation's raw full-rate comparison (validate_prediction); 0: differentiator_cutoff.
    // validation_settings sets it to the motion's own band when the differentiators were widened to the torque's.
    double raw_differentiator_cutoff = 0.0;
    double velocity_window = 0.0;        // s; Jacobi windows, override the cutoff
    double acceleration_window = 0.0;    // s
    double kappa = 6.0, mu = 6.0;
    int q = 2;
    // Exact (polynomial-exact on the sample grid) by default: short windows, e.g. at 100 Hz, have so few
    // taps that the trapezoidal rule misses the derivative's gain by tens of percent; for long windows
    // both agree.
    bool exact_discretization = true;
    double decimation_cutoff = 0.0;  // Hz; overrides the ratio
    int decimation = 0;              // factor; 0: about 4 samples per F_p cutoff period
    int decimation_order = 4;        // Butterworth order of F_p (doubled by forward-backward filtering)
    int butterworth_order = 4;       // order of F_q in the Butterworth method
    double min_joint_motion = 1e-3;  // rad: a joint whose position range is smaller "does not move"
    bool progress = false;           // stage timings on stderr
    int threads = 1;                 // threads for the regressor, F_p and the QR of one log (the result does not depend on it)
    std::size_t chunk = 1 << 15;     // samples per F_p chunk
    std::size_t plot_rows = 20000;   // decimated rows kept for plots
    // The regressor's velocities from the log's measured velocity columns (LogColumns::qd) instead of the
    // differentiated positions (identify --velocity measured); accelerations still come from the positions.
    bool measured_velocity = false;
    // The Coulomb columns s(alpha qd) from a velocity estimate whose cutoff is this multiple of the
    // differentiators' (or F_q's), put through the torque's filter after the sign function
    // (StateEstimates::qd_coulomb; docs/method.md "Coulomb columns"). 1: the same velocity as the other
    // columns; > 1: a wider one (switches closer to the true reversal, but carries more position noise
    // into the sign function); 0: off (the sign of the filtered velocity, unfiltered: the bias of issue 14);
    // < 0: auto, per joint the wider of 2 or 1.5 whose noise in the sign function stays within
    // kCoulombVelocityNoise (alpha sigma_v), else 1.
    double coulomb_velocity_ratio = -1.0;
    // Per joint, imposed (a validation log, the segments or logs of one identification: the plan's choice,
    // PipelineInfo::coulomb_velocity_ratios); non-empty overrides the automatic choice, not a 0 (off).
    std::vector<double> coulomb_velocity_ratios;
    // Lags of the residual autocorrelation accumulated with the factors (JointFactors::lagged; 0: none).
    int residual_lags = kDefaultResidualLags;
    // Only the log's samples [kept_from, kept_to) become equations (both 0: all); the samples around them
    // still feed the differentiators and F_p. identify --period: the middle copy of a tiled mean period
    // (periodic_log.hpp).
    std::size_t kept_from = 0, kept_to = 0;
    // False when this log's equations are stacked with other logs' and the caller checks their sum
    // (diagnose --in a.csv --in b.csv): a short log then need not hold more equations than parameters alone.
    bool require_own_equations = true;
};

// The positions and torques of a log, one column per joint (pointers into a CsvTable).
struct LogColumns {
    std::string source;
    double sample_period = 0.0;
    double start_time = 0.0;
    std::vector<const std::vector<double>*> q, tau;
    // Measured velocities (column qdJ, e.g. from --log-format's velocities), nullptr where not logged; used
    // with PipelineSettings::measured_velocity.
    std::vector<const std::vector<double>*> qd;
    // The reference the controller tracked (columns q_refJ, qd_refJ, or references: in --log-format), nullptr
    // where not logged; what the estimators IDIM-IV and DIDIM simulate the identified model along.
    std::vector<const std::vector<double>*> q_ref, qd_ref;
    std::vector<std::string> q_names, tau_names;
    // The same torque columns, writable, when their owner lets the identification align them in place (it
    // reads them no more: one method on the log's own table); empty: shift_torques aligns into a copy (an
    // hour of 6-axis torques is 173 MB, docs/performance.md).
    std::vector<std::vector<double>*> own_tau;
    // The delay (s) its torques are already read later by (a view of shift_torques): shift_torques aligns
    // them only by what is left of a delay.
    double tau_aligned_by = 0.0;
    std::size_t samples() const { return q.empty() ? 0 : q.front()->size(); }
};

struct PipelineInfo {
    Method method = Method::Jacobi;
    double sample_period = 0.0;
    std::size_t samples = 0;
    double bandwidth = 0.0;
    bool bandwidth_estimated = false;
    BandwidthEstimate bandwidth_estimate;  // what the automatic estimate saw (when bandwidth_estimated)
    double differentiator_cutoff = 0.0;  // wanted
    double velocity_window = 0.0, acceleration_window = 0.0;  // Jacobi, s
    double velocity_cutoff = 0.0, acceleration_cutoff = 0.0;  // achieved, Hz
    double prefilter_cutoff = 0.0;                            // Butterworth F_q, Hz
    std::vector<double> coulomb_velocity_cutoffs;             // Hz per joint, the Coulomb columns' velocity (empty: off)
    std::vector<double> coulomb_velocity_ratios;              // the ratios behind them (empty: off)
    double decimation_cutoff = 0.0;
    int decimation = 1;
    std::size_t first = 0, last = 0;  // valid derivative range [first, last) of input samples
    std::size_t crop = 0;             // F_p edge samples dropped at each end
    double seconds_differentiate = 0.0, seconds_regressor_filter = 0.0, seconds_ls = 0.0;
    std::vector<double> joint_range;  // rad
    std::vector<bool> joint_moves;
};

// Decimated, filtered rows kept for plots (the first plot_rows of them).
struct PlotRows {
    std::vector<double> t;
    std::vector<std::vector<double>> y;  // per joint
    std::vector<std::vector<double>> w;  // per joint, row-major rows x parameters
};

struct PipelineOutput {
    PipelineInfo info;
    JointFactors factors;
    PlotRows plot;
};

// One decimated sample as it enters the least squares: every joint's F_p-filtered regressor row and
// torque at full-rate sample `sample` of the log, and the unfiltered estimates the regressor was built from.
struct DecimatedRow {
    std::size_t sample = 0;      // index into the log's columns: the row's own sample, no time rounding
    double t = 0.0;              // s, log.start_time + sample * sample_period
    Eigen::MatrixXd w;           // joints x parameters: W after F_p
    Eigen::VectorXd y;           // joints: the torque after F_p (after F_q as well in the Butterworth method)
    Eigen::VectorXd q, qd, qdd;  // joints: the estimates at `sample` before F_p
};

// Receives what run_pipeline folds into the least squares, while it runs (the pipeline itself keeps no
// rows, so the sink decides what to store). Calls come from the calling thread, in increasing sample order;
// what they pass is valid during the call only (the pipeline reuses its buffers).
class RowSink {
public:
    virtual ~RowSink() = default;
    // Every decimated row, exactly the rows of the factors (the same numbers, not a recomputation).
    virtual void row(const DecimatedRow& row) = 0;
    // The full-rate torque after F_p (the signal Y is sampled from), joint j's samples
    // [first, first + count) at tau[j][0 .. count). The pieces arrive in order and cover the valid
    // derivative range [info.first, info.last) exactly once. Default: ignored.
    virtual void filtered_torque(std::size_t first, std::size_t count, const std::vector<const double*>& tau);
};

// Full-rate estimates on the valid range, shared by the pipeline and validation.
struct StateEstimates {
    std::size_t first = 0, last = 0;  // valid input samples [first, last)
    std::vector<std::vector<double>> q, qd, qdd, tau;  // per joint, full length (only [first, last) meaningful)
    // Coulomb columns (issue 14): a steep sign function s(alpha qd) does not commute with a low-pass, so
    // s(alpha qd^) of the filtered velocity is not the filtered s(alpha qd) the torque holds. When
    // qd_coulomb is set, fold_states evaluates the FCj columns on this wider velocity and then puts them
    // through the filter the torque went through (torque_fir: the Jacobi torque smoothing kernel; empty:
    // the Butterworth F_q), like the torque. Empty: the FCj columns come from qd as before.
    std::vector<std::vector<double>> qd_coulomb;
    std::vector<double> torque_fir;
};

// Resolves automatic choices (bandwidth, cutoffs, windows, decimation) and checks that the log is long
// enough; InputError names the option or the file otherwise.
PipelineInfo plan_pipeline(const LogColumns& log, const PipelineSettings& settings);
// The Coulomb columns' velocity ratio per joint for `log` (PipelineSettings::coulomb_velocity_ratio[s]; empty:
// off): imposed, given, or chosen from the joints' position noise and Coulomb slopes (without a model: 1).
// `info` from plan_pipeline on `log` (or the plan imposed on it).
std::vector<double> coulomb_velocity_ratios(const robot::RobotModel* model, const LogColumns& log, const PipelineSettings& settings,
                                            const PipelineInfo& info);
// `model`, if given, lets the automatic Coulomb velocity (PipelineSettings::coulomb_velocity_ratio < 0) see
// each joint's Coulomb smoothing alpha; without it that velocity is the other columns' (ratio 1).
StateEstimates estimate_states(const LogColumns& log, const PipelineSettings& settings, PipelineInfo& info,
                               const robot::RobotModel* model = nullptr);
// Steps 2-4 on given full-rate states (estimate_states', or a simulation's for the estimators IDIM-IV and
// DIDIM) with `info` from plan_pipeline on `log`: the same rows, F_p and decimation whatever the states.
PipelineOutput fold_states(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& settings, PipelineInfo info,
                           const StateEstimates& states, RowSink* rows = nullptr);
// `rows`, if given, receives every decimated row and the filtered torque (RowSink above).
PipelineOutput run_pipeline(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& settings,
                            RowSink* rows = nullptr);

}  // namespace jacobid::identify
