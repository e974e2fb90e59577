// SPDX-License-Identifier: MIT
#pragma once
// `jacobid diagnose` end to end: identify the nominal model as `jacobid identify` does, compare it with the
// data (torque residual, short-horizon simulation), locate the disagreement, select the missing effects
// (selection.hpp), re-identify with the augmented model and measure the gap before and after.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "diagnose/candidate_catalogue.hpp"
#include "diagnose/horizon_simulation.hpp"
#include "diagnose/residual_analysis.hpp"
#include "diagnose/selection.hpp"
#include "identify/solve/least_squares.hpp"
#include "identify/pipeline/pipeline.hpp"

namespace jacobid::diagnose {

struct DiagnoseSettings {
    identify::PipelineSettings pipeline;
    CatalogueSettings catalogue;
    SelectionSettings selection;
    HorizonSettings horizon;
};

// One model (nominal = before, augmented = after) measured against the data.
struct ModelSnapshot {
    identify::LsSolution solution;        // as `jacobid identify` reports it
    std::vector<double> residual_rms;     // per joint, N.m, identification rows (filtered, decimated)
    std::vector<double> heldout_rms;      // per joint, N.m, validation log or blocked cross-validation
    double heldout_weighted = 0.0;        // combined, in units of each joint's nominal sigma
    HorizonResult horizon;
    std::vector<Eigen::VectorXd> residual;  // per joint on the identification rows
    std::vector<JointResidualAnalysis> analysis;
};

struct EffectEstimate {
    sim::EffectTerm term;
    double value = 0.0, std = 0.0;  // std with the n_eff correction
    Eigen::VectorXd coefficients;   // of the term's columns
    CandidateTest test;             // the selection step that accepted it
};

struct Diagnosis {
    std::string log_source, validation_source, model_name;  // log_source: the logs' names joined with ", "
    std::vector<std::string> log_sources;                   // one per --in
    std::vector<std::string> joint_names;
    identify::PipelineInfo info;
    std::size_t catalogue_columns = 0;
    ModelSnapshot before, after;
    std::vector<EffectEstimate> effects;
    double delay = 0.0;
    SelectionResult selection;
    std::vector<std::string> notes;
    std::vector<Eigen::MatrixXd> state;  // per joint rows x 3 (q, qd, qdd) of the identification rows
    std::vector<double> t;
    std::string verdict;
    double seconds = 0.0;
};

using Progress = std::function<void(const std::string&)>;

Diagnosis run_diagnosis(const robot::RobotModel& nominal, const sim::EffectContext& context, const identify::LogColumns& log,
                        const identify::LogColumns* validation, const DiagnoseSettings& settings, const Progress& progress);
// Several logs diagnosed together (diagnose --in a.csv --in b.csv), as identify stacks them: the automatic
// choices resolved once on the longest log (identify::plan_segments) and imposed on every log, their rows
// stacked (stacked_decimated_rows: the selection's blocks and the residual analysis see them one after
// another), the identifications merged from every log's factors (identify::run_segmented_pipeline), the
// short-horizon simulations run on each log and pooled. One log is the single-log diagnosis above.
Diagnosis run_diagnosis(const robot::RobotModel& nominal, const sim::EffectContext& context, const std::vector<identify::LogColumns>& logs,
                        const identify::LogColumns* validation, const DiagnoseSettings& settings, const Progress& progress);

}  // namespace jacobid::diagnose
