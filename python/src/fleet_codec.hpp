// SPDX-License-Identifier: MIT
#pragma once
// The bytes a plan and a factor travel as (pickle, hence Dask): CBOR of their fields, each matrix as a bitmap of its
// non-zero entries and their raw doubles (-0.0, infinities and NaN kept exactly). A decoded plan or factor gives the same numbers as the original, so a
// fleet's workers and the driver compute what one process computes (tests/python/test_fleet.py).
#include <string>
#include <vector>

#include "identify/report/report.hpp"
#include "identify/pipeline/segmented_pipeline.hpp"
#include "job/identify_plan.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::python {

// What one log (or several, merged) reduced to, per method of its plan.
struct FactorData {
    std::vector<std::string> inputs;                 // the logs' names, in order
    std::vector<identify::SegmentReport> pieces;     // per piece (a log, or its segments with on_gap="split")
    std::vector<std::string> names;                  // per piece, for messages
    std::vector<identify::SegmentedOutput> methods;  // per method of the plan: the pieces' factors, merged in order
    double parse_seconds = 0.0;                      // reading the logs
};

std::string encode_plan(const std::vector<job::MethodPlan>& plan);
// The smoothed models are made again from `robot` (identify::make_chosen_model). InputError for bytes that are not a plan.
std::vector<job::MethodPlan> decode_plan(const std::string& bytes, const robot::RobotDescription& robot);

std::string encode_factor(const FactorData& factor);
FactorData decode_factor(const std::string& bytes);

}  // namespace jacobid::python
