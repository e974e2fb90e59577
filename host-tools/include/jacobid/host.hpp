// SPDX-License-Identifier: MIT
#pragma once
// jacobid::host in one include: robot descriptions and models, the closed-loop simulator, the identification
// pipeline with its least squares and validation (identify_log: the whole of `jacobid identify` on one log),
// Monte Carlo studies of it (`jacobid montecarlo`), and the model-discrepancy diagnosis. Single headers are
// <jacobid/host/MODULE/NAME.hpp> (e.g. <jacobid/host/identify/pipeline/pipeline.hpp>); errors are
// jacobid::InputError (<jacobid/host/core/errors.hpp>). Method: docs/method.md, diagnosis: docs/diagnose.md.
#include <jacobid/host/core/errors.hpp>
#include <jacobid/host/diagnose/diagnosis.hpp>
#include <jacobid/host/identify/identify_run.hpp>
#include <jacobid/host/identify/solve/least_squares.hpp>
#include <jacobid/host/identify/plan/log_columns.hpp>
#include <jacobid/host/identify/pipeline/pipeline.hpp>
#include <jacobid/host/identify/validation/validation.hpp>
#include <jacobid/host/io/csv_table.hpp>
#include <jacobid/host/montecarlo/study.hpp>
#include <jacobid/host/montecarlo/summary.hpp>
#include <jacobid/host/robot/robot_description.hpp>
#include <jacobid/host/robot/robot_model.hpp>
#include <jacobid/host/sim/augmented_model.hpp>
#include <jacobid/host/sim/effect_spec.hpp>
#include <jacobid/host/sim/measurement.hpp>
#include <jacobid/host/sim/simulator.hpp>
