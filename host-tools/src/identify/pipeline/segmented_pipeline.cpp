// SPDX-License-Identifier: MIT
#include "identify/pipeline/segmented_pipeline.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <exception>

#include "core/errors.hpp"
#include "core/parallel_for.hpp"
#include "identify/pipeline/merge_factors.hpp"
#include "identify/friction/torque_delay.hpp"
#include "identify/validation/validation.hpp"

namespace jacobid::identify {

std::string joined_reasons(const std::vector<std::string>& why) {
    std::string reasons;
    for (const std::string& w : why) {
        if (!w.empty()) reasons += (reasons.empty() ? "" : "; ") + w;
    }
    return reasons;
}

SegmentPlan plan_segments(const std::vector<LogColumns>& segments, const PipelineSettings& settings, const SegmentSource& source) {
    if (segments.empty()) throw InputError("no log segment to identify from");
    SegmentPlan plan;
    plan.source = source;
    for (std::size_t s = 1; s < segments.size(); ++s) {
        if (segments[s].samples() > segments[plan.reference].samples()) plan.reference = s;
    }
    const LogColumns& longest = segments[plan.reference];
    try {
        plan.info = plan_pipeline(longest, settings);
    } catch (const InputError& e) {
        throw InputError(fmt::format("{}: no {} is usable; the longest of the {}: {}", source.option, source.noun, segments.size(), e.what()));
    }
    // The same imposition as a validation log gets (bandwidth, windows, cutoffs), plus the decimation factor.
    plan.fixed = validation_settings(settings, plan.info);
    plan.fixed.decimation = plan.info.decimation;
    plan.fixed.progress = settings.progress;
    return plan;
}

SegmentedOutput run_segmented_pipeline(const robot::RobotModel& model, const std::vector<LogColumns>& segments, const SegmentPlan& plan,
                                       double torque_delay, int threads, const NextSegment& more) {
    SegmentedOutput out;
    PipelineInfo& info = out.merged.info;
    PlotRows& plot = out.merged.plot;
    std::size_t samples = 0;
    double seconds_differentiate = 0.0, seconds_filter = 0.0, seconds_ls = 0.0;
    std::vector<double> range;
    // Threads left over when there are fewer pieces than threads go inside each piece's pipeline.
    PipelineSettings fixed = plan.fixed;
    fixed.threads = std::max(1, threads / static_cast<int>(std::max<std::size_t>(1, segments.size())));
    // The Coulomb columns' velocity too is chosen once, on the longest piece with the model as smoothed:
    // each piece choosing from its own noise estimate made a log split at a gap differ from its halves.
    if (fixed.coulomb_velocity_ratios.empty()) fixed.coulomb_velocity_ratios = coulomb_velocity_ratios(&model, segments[plan.reference], fixed, plan.info);
    // One piece's result, merged (or its reason for not being used recorded) in piece order.
    const auto absorb = [&](PipelineOutput& part, const std::exception_ptr& error) {
        out.used.push_back(false);
        out.why.emplace_back();
        out.rows.push_back(0);
        if (error) {
            try {
                std::rethrow_exception(error);
            } catch (const InputError& e) {
                out.why.back() = e.what();
                return;
            }
        }
        if (out.used_count == 0) info = part.info;
        out.used.back() = true;
        ++out.used_count;
        samples += part.info.samples;
        seconds_differentiate += part.info.seconds_differentiate;
        seconds_filter += part.info.seconds_regressor_filter;
        seconds_ls += part.info.seconds_ls;
        range.resize(part.info.joint_range.size(), 0.0);
        for (std::size_t j = 0; j < range.size(); ++j) range[j] = std::max(range[j], part.info.joint_range[j]);
        out.rows.back() = part.factors.rows.empty() ? 0 : part.factors.rows.front();
        merge_factors(out.merged.factors, part.factors);
        part.factors = JointFactors{};  // merged: free it before the next segment
        // Plot rows of the segments one after another, at their true times.
        const std::size_t take = std::min(part.plot.t.size(), plan.fixed.plot_rows - std::min(plan.fixed.plot_rows, plot.t.size()));
        const std::size_t c = part.plot.t.empty() ? 0 : part.plot.w.front().size() / part.plot.t.size();
        plot.y.resize(part.plot.y.size());
        plot.w.resize(part.plot.w.size());
        plot.t.insert(plot.t.end(), part.plot.t.begin(), part.plot.t.begin() + static_cast<std::ptrdiff_t>(take));
        for (std::size_t j = 0; j < part.plot.y.size(); ++j) {
            plot.y[j].insert(plot.y[j].end(), part.plot.y[j].begin(), part.plot.y[j].begin() + static_cast<std::ptrdiff_t>(take));
            plot.w[j].insert(plot.w[j].end(), part.plot.w[j].begin(), part.plot.w[j].begin() + static_cast<std::ptrdiff_t>(take * c));
        }
    };
    const auto identify_piece = [&](const LogColumns& piece) {
        const ShiftedTorques aligned = shift_torques(piece, torque_delay);
        return run_pipeline(model, aligned.log, fixed);
    };
    {
        // Each segment on its own (threads), then merged in segment order: the thread count changes no bit.
        std::vector<PipelineOutput> parts(segments.size());
        ParallelForOptions pool;
        pool.threads = threads;
        pool.stop_on_failure = false;
        const std::vector<std::exception_ptr> errors = parallel_for(segments.size(), pool, [&](std::size_t s) { parts[s] = identify_piece(segments[s]); });
        for (std::size_t s = 0; s < segments.size(); ++s) absorb(parts[s], errors[s]);
    }
    if (more) {
        fixed.threads = threads;
        LogColumns piece;
        while (more(piece)) {
            PipelineOutput part;
            std::exception_ptr error;
            try {
                part = identify_piece(piece);
            } catch (const InputError&) {
                error = std::current_exception();
            }
            absorb(part, error);
        }
    }
    const std::size_t count = out.used.size();
    if (out.used_count == 0) {
        throw InputError(fmt::format("{}: none of the {} {}s is usable: {}", plan.source.option, count, plan.source.noun, joined_reasons(out.why)));
    }
    info.samples = samples;
    info.bandwidth_estimated = plan.info.bandwidth_estimated;
    info.bandwidth_estimate = plan.info.bandwidth_estimate;
    info.seconds_differentiate = seconds_differentiate;
    info.seconds_regressor_filter = seconds_filter;
    info.seconds_ls = seconds_ls;
    info.joint_range = range;
    info.joint_moves.assign(range.size(), false);
    for (std::size_t j = 0; j < range.size(); ++j) info.joint_moves[j] = range[j] > plan.fixed.min_joint_motion;
    return out;
}

}  // namespace jacobid::identify
