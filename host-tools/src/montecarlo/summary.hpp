// SPDX-License-Identifier: MIT
#pragma once
// Per method and parameter, what a Monte Carlo study says about the identification (issue 14's table):
// is it unbiased (mean error against its standard error), and are its reported standard deviations honest
// (spread of the estimates against the mean reported std, coverage of the truth by +-2 reported std).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "montecarlo/study.hpp"

namespace jacobid::montecarlo {

// The bands a sound identification meets (issue 14's acceptance).
struct Acceptance {
    double max_error_percent = 0.1;  // |mean error| within this, or
    double standard_errors = 3.0;    // within this many standard errors of the mean
    double min_coverage = 0.9;       // fraction of runs with |x - truth| <= 2 reported std
    double min_spread = 0.8, max_spread = 1.25;  // empirical std / mean reported std
};

struct ParameterSummary {
    std::string name;
    double truth = 0.0;
    int runs = 0;                         // runs that identified the parameter (the statistics use these)
    double mean = 0.0;
    double mean_error_percent = 0.0;      // 100 (mean - truth) / |truth|
    double standard_error_percent = 0.0;  // 100 (empirical_std / sqrt(runs)) / |truth|
    double empirical_std = 0.0;           // sample standard deviation of the estimates (runs - 1)
    double mean_reported_std = 0.0;       // mean of the identification's sigma_X
    double spread_ratio = 0.0;            // empirical_std / mean_reported_std
    double coverage_2std = 0.0;           // fraction of runs whose truth lies within +-2 reported std
    bool within_3se = false;              // |mean - truth| <= standard_errors x standard error
    bool error_ok = false, spread_ok = false, coverage_ok = false;
    bool ok() const { return error_ok && spread_ok && coverage_ok; }
};

// NaN statistics (null in JSON) where fewer than 2 runs identified the parameter or the truth is 0 (percentages).
std::vector<ParameterSummary> summarize(const Study& study, const MethodRuns& runs, const Acceptance& acceptance = {});

}  // namespace jacobid::montecarlo
