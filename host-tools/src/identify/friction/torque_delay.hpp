// SPDX-License-Identifier: MIT
#pragma once
// Time alignment of the torque channel (identify --torque-delay auto|SECONDS).
//
// A constant offset between the torque and the position channels biases friction (a torque command held
// over the control period is half a sample early; CAN frames of different drives arrive at different
// times): with a half-sample lead the simulated 2R's FV1 comes out 14 % low and FC1 8 % high. The offset is
// estimated by least squares: the torque read `delay` later (linear interpolation of the raw torque, which
// is flat in the band F_p keeps) is identified again, and the residual sum of squares RSS(delay) is
// minimized on a one-sample grid refined by a parabola through the three best points (RSS is quadratic in
// a small shift: e(d) = e(0) + d dtau/dt). Its standard deviation is the sandwich of the score RSS'/2 with the
// rows' serial correlation (Newey-West over the decimated rows, corrected for the fit's leverage;
// torque_delay_std.hpp, docs/method.md "Torque delay"): the independent-rows 2 sigma^2 / RSS'' was about 2 x too
// small on excite's designs, and the 3-std test fired on 17-23 % of delay-free simulated logs.
// Convention: `delay` > 0 means the torque channel lags the positions (it is read later to align it).
#include <cstddef>
#include <string>
#include <vector>

#include "identify/solve/least_squares.hpp"
#include "identify/pipeline/pipeline.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::identify {

// Linear interpolation of x at fractional index `at`, held at the ends of the record.
double sample_at(const std::vector<double>& x, double at);

// Torque columns of `log` read `delay` seconds later (linear interpolation, held at the ends), and a view
// of the log that uses them (positions shared with `log`, which must outlive it). A zero delay copies
// nothing: the view is `log` itself, as is a delay its torques are already aligned by
// (log.tau_aligned_by). With `log.own_tau` given, the columns are aligned in place (the same
// values) and the view, which is `log` without own_tau, is the only one to read them afterwards.
struct ShiftedTorques {
    std::vector<std::vector<double>> tau;
    LogColumns log;
};
ShiftedTorques shift_torques(const LogColumns& log, double delay);

struct TorqueDelaySettings {
    double max_delay = 0.0;        // s, search range +-max_delay; 0: 5 samples
    double significance = 3.0;     // compensate only when |delay| > significance x std
    std::size_t max_samples = std::size_t{1} << 17;  // longer logs: estimated on their first max_samples (0: all)
};

struct TorqueDelayEstimate {
    double delay = 0.0;        // s, the least-squares estimate
    double std_dev = 0.0;      // s
    // Bartlett lags of std_dev's long-run variance (0: rows taken as independent). Not in the JSON yet: the
    // fleet's plan codec (python/src/fleet_codec.cpp) would have to carry it for the fleet's JSON to match.
    int std_lags = 0;
    bool compensated = false;  // the identification used the shifted torques
    bool at_bound = false;     // the minimum lies at +-max_delay: the true offset may be larger
    int evaluations = 0;       // identifications run
    std::size_t samples_used = 0;  // the log's first samples the estimate used
    std::vector<double> grid, rss;  // the RSS curve (s, N.m^2)
};

// What identify used: the estimate (auto) or the user's value (given), and the shift applied.
struct TorqueDelayResult {
    bool given = false;
    TorqueDelayEstimate estimate;
    double applied() const { return estimate.compensated ? estimate.delay : 0.0; }
};

// "torque delay +0.500 ms (std 0.004 ms, estimated; compensated)"
std::string describe(const TorqueDelayResult& r);

TorqueDelayEstimate estimate_torque_delay(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& pipeline,
                                          const SolveOptions& solve, const TorqueDelaySettings& settings = {});

}  // namespace jacobid::identify
