// SPDX-License-Identifier: MIT
#include "options/diagnose_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>

#include "options/fit_options.hpp"
#include "options/option_checks.hpp"

namespace jacobid::options {

void add_diagnose_search_options(CLI::App* cmd, diagnose::DiagnoseSettings& settings, bool& no_delay) {
    cmd->add_option("--alpha", settings.selection.alpha, "significance level of each step (Bonferroni over all candidates tried)")
        ->check(number_between(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--min-gain", settings.selection.min_gain, "minimum relative reduction of the held-out error for a candidate to be named")
        ->check(number_in(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--max-effects", settings.selection.max_effects, "stop after naming this many effects")
        ->check(whole_number_from(0))
        ->capture_default_str();
    cmd->add_option("--folds", settings.selection.folds, "blocks of the blocked cross-validation (without --validate)")
        ->check(whole_number_from(2))
        ->capture_default_str();
    cmd->add_option("--max-delay", settings.selection.max_delay, "torque delays searched in [-max, max] s")->check(positive_number())->capture_default_str();
    cmd->add_flag("--no-delay", no_delay, "do not search a torque delay");
    cmd->add_option("--max-cogging-order", settings.catalogue.max_cogging_order, "cogging harmonics tried: 2..this order per revolution")
        ->check(whole_number_from(1))
        ->capture_default_str();
    cmd->add_option("--horizon", settings.horizon.horizon, "length of the short-horizon simulations in s")->check(positive_number())->capture_default_str();
    cmd->add_option("--horizon-spacing", settings.horizon.spacing, "time between the starts of the short-horizon simulations in s")
        ->check(positive_number())
        ->capture_default_str();
    add_pipeline_rate_options(cmd, settings.pipeline);
}

// The search's sizes that follow from the options and the log, refused before the search allocates them.
// The bounds are far above any real use: 1000 folds (5 is the default), a delay grid of 20001 one-sample
// shifts (+-10 s at 1 kHz), 100000 cogging candidates (30 orders per joint is the default).
void refuse_oversized_search(const diagnose::DiagnoseSettings& settings, const identify::LogColumns& log, const robot::RobotModel& model,
                             std::size_t total_samples) {
    const auto& s = settings.selection;
    const double joints = model.joint_count(), columns = model.parameter_count();
    const double samples = static_cast<double>(total_samples > 0 ? total_samples : log.samples());
    // Each fold keeps one Gram matrix per joint.
    refuse_oversized(fmt::format("--folds {}", s.folds), s.folds, 1000, "folds", joints * columns * columns * 8.0, "lower --folds");
    // Each delay candidate re-solves the selection with the torques shifted by one more sample (a cost in time).
    refuse_oversized(fmt::format("--max-delay {:g} s at the log's sample period {:g} s", s.max_delay, log.sample_period),
                     2.0 * std::round(s.max_delay / log.sample_period) + 1.0, 20001, "delay candidates", 0.0, "lower --max-delay");
    // Each cogging order adds a sine and a cosine column over the whole log, per joint.
    refuse_oversized(fmt::format("--max-cogging-order {}", settings.catalogue.max_cogging_order),
                     joints * (settings.catalogue.max_cogging_order - 1), 1e5, "cogging candidates", 2.0 * samples * 8.0,
                     "lower --max-cogging-order");
}

}  // namespace jacobid::options
