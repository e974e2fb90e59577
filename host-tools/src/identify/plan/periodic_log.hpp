// SPDX-License-Identifier: MIT
#pragma once
// identify --period: a log that repeats one trajectory (jacobid excite + simulate --trajectory, or a robot
// playing an excitation period after period) is averaged over its whole periods before the pipeline
// (docs/method.md, "Periodic logs"; Swevers et al. 1997):
//   - periods that are not the same motion (a start-up transient) are left out, by their positions' spread;
//   - the noise of the averaged torques and positions falls by sqrt(M) over M periods, and what differs
//     from period to period is noise: its variance per joint, from the spread about the mean, gives the
//     weights of the least squares (--estimator wls) instead of residuals that also hold model error;
//   - the averaged period is a periodic signal: tiled before and after itself, it feeds the unchanged
//     pipeline, whose differentiator and F_p transients then fall on the copies, and only the middle copy's
//     samples become equations (PipelineSettings::kept_from/kept_to): no edge of the period is lost.
// The period is given (seconds, a whole number of samples over the log) or detected from the positions: the
// first clear minimum of the normalized mismatch between the log and itself shifted by a lag, after the
// motion has decorrelated.
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "identify/pipeline/pipeline.hpp"

namespace jacobid::identify {

struct PeriodicLog {
    // The averaged period tiled `tiles` times; its middle copy is [kept_from, kept_to).
    LogColumns columns;
    std::size_t kept_from = 0, kept_to = 0;
    double period = 0.0;             // s, samples_per_period x sample period
    bool detected = false;           // false: given with --period
    double detection_mismatch = 0.0;  // detected: the mismatch at the period (0: exactly periodic, 1: unrelated)
    std::size_t samples_per_period = 0;
    std::size_t periods = 0;          // whole periods in the log
    std::vector<std::size_t> skipped_periods;  // 1-based: whole periods not averaged (not the same motion)
    std::size_t dropped_samples = 0;  // after the last whole period
    std::vector<double> torque_noise;    // per joint, std of one period's torque about the mean (N.m or N)
    std::vector<double> position_noise;  // per joint, the same for the positions (rad or m)
    std::vector<double> wrap_jump;       // per joint, |q(end of period) - q(start)| of the mean period
    std::vector<std::string> warnings;

    PeriodicLog() = default;
    PeriodicLog(const PeriodicLog&) = delete;  // columns point into the owned data below
    PeriodicLog& operator=(const PeriodicLog&) = delete;

    std::vector<std::vector<double>> q, tau, qd, q_ref, qd_ref;  // owned data behind `columns`
};

// The period of `log` from its moving joints' positions; InputError naming the log when none is clear.
// Returns the lag in samples and the mismatch there.
struct DetectedPeriod {
    std::size_t samples = 0;
    double mismatch = 0.0;
};
DetectedPeriod detect_period(const LogColumns& log, double min_joint_motion);

// Averages `log` over its whole periods (`period` in s, or detected when nullopt). InputError when the
// period is not a whole number of samples (to a quarter sample over the log), or the log holds fewer than
// two periods.
std::unique_ptr<PeriodicLog> average_periods(const LogColumns& log, std::optional<double> period, double min_joint_motion, int tiles = 5);

// PipelineSettings that make only the middle copy's samples equations.
PipelineSettings periodic_settings(PipelineSettings settings, const PeriodicLog& periodic);

// One line for stderr and the text report; the JSON object "period" of identify's output.
std::string describe(const PeriodicLog& periodic);
nlohmann::json to_json(const PeriodicLog& periodic);

// "--period auto|SECONDS" parsed: nullopt for auto; InputError for anything else.
std::optional<double> parse_period_option(const std::string& text);

}  // namespace jacobid::identify
