// SPDX-License-Identifier: MIT
#pragma once
// The identification pipeline on a log split at its gaps (--on-gap split, docs/log-format.md): every
// segment goes through run_pipeline on its own (its own differentiator edges and F_p transients cropped,
// so no window straddles a gap) and the per-joint factors are stacked (merge_factors). The automatic
// choices (bandwidth, cutoffs, Jacobi windows, decimation) are resolved once, on the longest segment, and
// imposed on every segment, so all equations come from the same filters. A segment too short for them is
// not used, with the pipeline's reason; only when no segment is usable is it an error.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "identify/pipeline/pipeline.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::identify {

// What the pieces are, for messages: the segments of one log cut at its gaps, or several logs (--in a --in b).
struct SegmentSource {
    std::string option = "--on-gap split";
    std::string noun = "segment";
};

struct SegmentPlan {
    SegmentSource source;
    std::size_t reference = 0;  // the longest segment, where the automatic choices were resolved
    PipelineInfo info;          // its plan
    PipelineSettings fixed;     // `settings` with those choices imposed, for every segment
};

// InputError (naming the longest segment) when even the longest segment cannot be planned.
SegmentPlan plan_segments(const std::vector<LogColumns>& segments, const PipelineSettings& settings, const SegmentSource& source = {});
// `settings` with the choices of a plan `info` imposed (what plan_segments puts in SegmentPlan::fixed), so that a
// plan carried elsewhere (a fleet's worker, job/log_factor.hpp) is imposed the same way.
PipelineSettings imposed_settings(const PipelineSettings& settings, const PipelineInfo& info);

struct SegmentedOutput {
    // Factors of every used segment stacked; info of the first used segment with samples = the used
    // segments' total, the bandwidth estimate of the plan and joint ranges over the used segments; plot
    // rows of the segments in order (up to plot_rows).
    PipelineOutput merged;
    std::vector<bool> used;        // per segment
    std::vector<std::string> why;  // per segment: the pipeline's reason when not used, else empty
    std::vector<std::size_t> rows; // per segment: its equations (decimated rows per joint); 0 when not used
    std::size_t used_count = 0;
};

// One piece through the pipeline with the plan's settings `fixed`, its torques shifted by `torque_delay`: an
// output of that one piece, used, or not used with the pipeline's reason (its InputError caught). Its
// merged.info holds the piece's figures (samples, timings, joint ranges), which merge_segments adds up.
SegmentedOutput fold_segment(const robot::RobotModel& model, const LogColumns& piece, const PipelineSettings& fixed, double torque_delay);

// Appends `part`'s pieces after `total`'s: their factors stacked (merge_factors), the figures added up, the
// info of the first used piece kept, plot rows up to `plot_rows`. Associative: any bracketing of the same
// piece order gives the same pieces and figures, and the same factors up to rounding, so a tree reduction
// over a fleet's logs is the same as the left fold run_segmented_pipeline does.
void merge_segments(SegmentedOutput& total, SegmentedOutput part, std::size_t plot_rows);

// Merges pieces in their order by an ordered binary tree: adjacent pairs, then adjacent pairs of those, an odd last
// one carried up, whether the pieces come at once or one by one (a binary counter: at most log2(n) partial results
// held). The merge of stacked triangles is associative only up to rounding, so one bracketing for every count is
// what makes `identify --in ...` (run_segmented_pipeline) and a fleet's tree reduction on Dask
// (python/jacobid/_fleet_tree.py, the same pairs) agree bit for bit.
class OrderedMerge {
public:
    explicit OrderedMerge(std::size_t plot_rows) : plot_rows_(plot_rows) {}
    void add(SegmentedOutput part);
    // Everything added, merged (empty when nothing was).
    SegmentedOutput result();

private:
    std::size_t plot_rows_;
    std::vector<std::pair<int, SegmentedOutput>> stack_;  // (level, partial result) in piece order
};

// The merged output of every piece completed: InputError when none is usable (naming each one's reason), the
// plan's bandwidth estimate, which joints move.
void finish_segments(SegmentedOutput& out, const SegmentPlan& plan);

// Pieces produced one at a time after the given ones (a long CSV log read piece by piece, io/csv_pieces.hpp):
// fills `piece` and returns true, or returns false when none is left. Each piece is identified on every
// thread and merged before the next is asked for, so that one piece at a time is held; its columns must
// stay valid until the next call.
using NextSegment = std::function<bool(LogColumns& piece)>;

// `torque_delay` (s) is applied to every segment (shift_torques). The segments run on up to `threads`
// threads and are merged in their order, then those of `more`, so the result does not depend on the thread
// count. InputError when no segment is usable, naming each one's reason.
SegmentedOutput run_segmented_pipeline(const robot::RobotModel& model, const std::vector<LogColumns>& segments, const SegmentPlan& plan,
                                       double torque_delay, int threads = 1, const NextSegment& more = {});

// "reason 1; reason 2; ..." of the segments not used (their non-empty `why`), for one-line errors.
std::string joined_reasons(const std::vector<std::string>& why);

}  // namespace jacobid::identify
