// SPDX-License-Identifier: MIT
#pragma once
// Steps 2-4 of the pipeline (docs/method.md "Identification pipeline"): on the state estimates a StateSource
// hands out chunk by chunk, the regressor and the torque of every sample, F_p on every column, decimation,
// and each joint's rows folded into its running QR factor (and the lagged products the std needs). Only a
// chunk's columns are held at a time. pipeline.cpp plans the log and estimates the states; this folds them.
#include "identify/pipeline/pipeline.hpp"
#include "identify/pipeline/state_source.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::identify {

// `planned`: plan_pipeline's result (windows, F_p, decimation, crop). `sink` (may be null) receives the
// filtered torques and the decimated rows.
PipelineOutput fold_source(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& s, PipelineInfo planned,
                           const StateSource& states, RowSink* sink);

}  // namespace jacobid::identify
