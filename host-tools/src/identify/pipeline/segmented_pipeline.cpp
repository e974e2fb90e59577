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
    plan.fixed = imposed_settings(settings, plan.info);
    return plan;
}

PipelineSettings imposed_settings(const PipelineSettings& settings, const PipelineInfo& info) {
    // The same imposition as a validation log gets (bandwidth, windows, cutoffs), plus the decimation factor.
    PipelineSettings fixed = validation_settings(settings, info);
    fixed.decimation = info.decimation;
    fixed.progress = settings.progress;
    return fixed;
}

SegmentedOutput fold_segment(const robot::RobotModel& model, const LogColumns& piece, const PipelineSettings& fixed, double torque_delay) {
    SegmentedOutput out;
    out.used.push_back(false);
    out.why.emplace_back();
    out.rows.push_back(0);
    try {
        const ShiftedTorques aligned = shift_torques(piece, torque_delay);
        out.merged = run_pipeline(model, aligned.log, fixed);
    } catch (const InputError& e) {
        out.why.back() = e.what();
        return out;
    }
    out.used.back() = true;
    out.used_count = 1;
    out.rows.back() = out.merged.factors.rows.empty() ? 0 : out.merged.factors.rows.front();
    return out;
}

void merge_segments(SegmentedOutput& total, SegmentedOutput part, std::size_t plot_rows) {
    total.used.insert(total.used.end(), part.used.begin(), part.used.end());
    total.why.insert(total.why.end(), part.why.begin(), part.why.end());
    total.rows.insert(total.rows.end(), part.rows.begin(), part.rows.end());
    if (part.used_count == 0) return;
    PipelineInfo& info = total.merged.info;
    const PipelineInfo& add = part.merged.info;
    if (total.used_count == 0) {
        info = add;  // the first used piece's info; its figures start the sums
    } else {
        info.samples += add.samples;
        info.seconds_differentiate += add.seconds_differentiate;
        info.seconds_regressor_filter += add.seconds_regressor_filter;
        info.seconds_ls += add.seconds_ls;
        info.joint_range.resize(std::max(info.joint_range.size(), add.joint_range.size()), 0.0);
        for (std::size_t j = 0; j < add.joint_range.size(); ++j) info.joint_range[j] = std::max(info.joint_range[j], add.joint_range[j]);
    }
    total.used_count += part.used_count;
    merge_factors(total.merged.factors, part.merged.factors);
    part.merged.factors = JointFactors{};  // merged: free it before the next piece
    // Plot rows of the pieces one after another, at their true times.
    PlotRows& plot = total.merged.plot;
    const PlotRows& more = part.merged.plot;
    const std::size_t take = std::min(more.t.size(), plot_rows - std::min(plot_rows, plot.t.size()));
    const std::size_t c = more.t.empty() ? 0 : more.w.front().size() / more.t.size();
    plot.y.resize(std::max(plot.y.size(), more.y.size()));
    plot.w.resize(std::max(plot.w.size(), more.w.size()));
    plot.t.insert(plot.t.end(), more.t.begin(), more.t.begin() + static_cast<std::ptrdiff_t>(take));
    for (std::size_t j = 0; j < more.y.size(); ++j) {
        plot.y[j].insert(plot.y[j].end(), more.y[j].begin(), more.y[j].begin() + static_cast<std::ptrdiff_t>(take));
        plot.w[j].insert(plot.w[j].end(), more.w[j].begin(), more.w[j].begin() + static_cast<std::ptrdiff_t>(take * c));
    }
}

void OrderedMerge::add(SegmentedOutput part) {
    stack_.emplace_back(0, std::move(part));
    while (stack_.size() > 1 && stack_[stack_.size() - 1].first == stack_[stack_.size() - 2].first) {
        auto [level, right] = std::move(stack_.back());
        stack_.pop_back();
        merge_segments(stack_.back().second, std::move(right), plot_rows_);
        stack_.back().first = level + 1;
    }
}

SegmentedOutput OrderedMerge::result() {
    // The carried-up odd ones join from the right: the bracketing of a level-by-level pairing.
    while (stack_.size() > 1) {
        SegmentedOutput right = std::move(stack_.back().second);
        stack_.pop_back();
        merge_segments(stack_.back().second, std::move(right), plot_rows_);
    }
    SegmentedOutput out = stack_.empty() ? SegmentedOutput{} : std::move(stack_.back().second);
    stack_.clear();
    return out;
}

void finish_segments(SegmentedOutput& out, const SegmentPlan& plan) {
    if (out.used_count == 0) {
        throw InputError(fmt::format("{}: none of the {} {}s is usable: {}", plan.source.option, out.used.size(), plan.source.noun, joined_reasons(out.why)));
    }
    PipelineInfo& info = out.merged.info;
    info.bandwidth_estimated = plan.info.bandwidth_estimated;
    info.bandwidth_estimate = plan.info.bandwidth_estimate;
    info.joint_moves.assign(info.joint_range.size(), false);
    for (std::size_t j = 0; j < info.joint_range.size(); ++j) info.joint_moves[j] = info.joint_range[j] > plan.fixed.min_joint_motion;
}

SegmentedOutput run_segmented_pipeline(const robot::RobotModel& model, const std::vector<LogColumns>& segments, const SegmentPlan& plan,
                                       double torque_delay, int threads, const NextSegment& more) {
    OrderedMerge merged(plan.fixed.plot_rows);
    // Threads left over when there are fewer pieces than threads go inside each piece's pipeline.
    PipelineSettings fixed = plan.fixed;
    fixed.threads = std::max(1, threads / static_cast<int>(std::max<std::size_t>(1, segments.size())));
    // The Coulomb columns' velocity too is chosen once, on the longest piece with the model as smoothed:
    // each piece choosing from its own noise estimate made a log split at a gap differ from its halves.
    if (fixed.coulomb_velocity_ratios.empty()) fixed.coulomb_velocity_ratios = coulomb_velocity_ratios(&model, segments[plan.reference], fixed, plan.info);
    {
        // Each segment on its own (threads), then merged in segment order (OrderedMerge): the thread count changes no bit.
        std::vector<SegmentedOutput> parts(segments.size());
        ParallelForOptions pool;
        pool.threads = threads;
        const std::vector<std::exception_ptr> errors =
            parallel_for(segments.size(), pool, [&](std::size_t s) { parts[s] = fold_segment(model, segments[s], fixed, torque_delay); });
        for (const auto& e : errors) {
            if (e) std::rethrow_exception(e);  // not an InputError (fold_segment keeps those as the piece's reason): a bug
        }
        for (SegmentedOutput& part : parts) merged.add(std::move(part));
    }
    if (more) {
        fixed.threads = threads;
        LogColumns piece;
        while (more(piece)) merged.add(fold_segment(model, piece, fixed, torque_delay));
    }
    SegmentedOutput out = merged.result();
    finish_segments(out, plan);
    return out;
}

}  // namespace jacobid::identify
