// SPDX-License-Identifier: MIT
#pragma once
// `jacobid payload --unloaded`: the loaded and the unloaded run of one trajectory are recorded separately, so
// their samples do not line up (another start, another clock, another grid). The shift s that makes
// q_unloaded(t + s) match q_loaded(t) best (least squares over every joint's position) is searched on a coarse
// grid over the whole overlap, then refined at a tenth of the loaded log's period with linear interpolation.
// Both runs are then put on the loaded run's grid over the overlap (aligned_pair), for the payload estimate
// to subtract the unloaded run's residual against the arm model from the loaded run's, row by row
// (payload_rows.hpp): what the arm's model lacks (friction, unmodelled dynamics) cancels where the motions agree.
#include <string>
#include <vector>

#include "identify/pipeline/pipeline.hpp"

namespace jacobid::payload {

struct Alignment {
    double shift = 0.0;            // s: unloaded time = loaded time (from its first sample) + shift
    double resolution = 0.0;       // s: the refinement's step
    double position_rms = 0.0;     // rad: RMS of q_loaded - q_unloaded over joints and the overlap after the shift
    double motion_rms = 0.0;       // rad: RMS of the loaded positions about their means (the scale position_rms is judged on)
    std::size_t first = 0, last = 0;  // the loaded log's samples [first, last) that the unloaded run covers
};

// InputError when the logs have different joint counts or overlap over less than half the shorter one.
Alignment align_runs(const identify::LogColumns& loaded, const identify::LogColumns& unloaded);

// A log that owns its columns (the views of LogColumns point into q and tau; moving keeps them valid).
struct OwnedLog {
    std::vector<std::vector<double>> q, tau;
    identify::LogColumns log;
};
// Both runs on the loaded run's grid over the overlap: the loaded samples [first, last) as they are, the
// unloaded run interpolated (linearly) at the same instants plus the shift. Their pipelines then give rows at
// the same samples, so that the two runs' equations can be subtracted row by row.
struct AlignedPair {
    OwnedLog loaded, unloaded;
};
AlignedPair aligned_pair(const identify::LogColumns& loaded, const identify::LogColumns& unloaded, const Alignment& a);

}  // namespace jacobid::payload
