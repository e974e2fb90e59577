// SPDX-License-Identifier: MIT
#pragma once
// What the pipeline's fold (regressor, F_p, decimation, factors) reads chunk by chunk: every joint's
// full-rate estimates over a range of samples. Two sources give the same numbers:
//  - HeldStates: estimates computed for the whole log beforehand (StateEstimates: the Butterworth baseline,
//    measured velocities, the simulated states of IDIM-IV and DIDIM);
//  - StreamedJacobiStates: the Jacobi estimates computed range by range from the log's raw positions and
//    torques when a chunk asks for them, so that no full-length estimate is ever held (issue 18: one hour of
//    6-axis data held 0.86 GB of them). An FIR has finite reach: the outputs of a range need the inputs of
//    that range plus the kernel's half width, all of which the log holds.
#include <cstddef>
#include <string>
#include <vector>

#include "core/parallel_for.hpp"
#include "identify/pipeline/pipeline.hpp"

namespace jacobid::identify {

// The centered FIR `w` (odd length 2h + 1) of x at samples [from, from + out.size()): out[k - from] is the
// output that belongs to input sample k (the correlation of w with x[k - h .. k + h]) where h <= k < n - h,
// `before` below that range and `after` above it. The whole log (from 0, out.size() == x.size()) is what
// estimate_states holds; any range of it is what StreamedJacobiStates computes. InputError names `source`.
void centered_fir_range(const std::vector<double>& w, const std::vector<double>& x, std::size_t from, std::vector<double>& out, double before,
                        double after, const std::string& source);

// Per joint, samples [from, to) of the estimates (index k - from).
struct StateWindow {
    std::size_t from = 0, to = 0;
    std::vector<std::vector<double>> q, qd, qdd, tau, qd_coulomb;  // qd_coulomb empty when the Coulomb velocity is off
};

class StateSource {
public:
    virtual ~StateSource() = default;
    virtual std::size_t samples() const = 0;  // of the log
    // The Coulomb columns' own velocity is given (StateEstimates::qd_coulomb), and the filter the torque
    // went through (empty: the Butterworth F_q).
    virtual bool has_coulomb_velocity() const = 0;
    virtual const std::vector<double>& torque_fir() const = 0;
    // Fills `window` with [from, to) (to <= samples()); `pool` may split the joints over threads.
    virtual void load(std::size_t from, std::size_t to, StateWindow& window, const ParallelForOptions& pool) const = 0;
};

class HeldStates final : public StateSource {
public:
    explicit HeldStates(const StateEstimates& estimates) : e_(estimates) {}
    std::size_t samples() const override { return e_.q.empty() ? 0 : e_.q.front().size(); }
    bool has_coulomb_velocity() const override { return !e_.qd_coulomb.empty(); }
    const std::vector<double>& torque_fir() const override { return e_.torque_fir; }
    void load(std::size_t from, std::size_t to, StateWindow& window, const ParallelForOptions& pool) const override;

private:
    const StateEstimates& e_;
};

// The Jacobi method's kernels for one log (estimate_states designs them the same way).
struct JacobiKernels {
    std::vector<double> velocity, acceleration;
    std::vector<double> torque;                // the velocity kernel's low-pass (torque_smoothing.hpp)
    std::vector<std::vector<double>> coulomb;  // per joint, the Coulomb columns' velocity kernel; empty: off
};

class StreamedJacobiStates final : public StateSource {
public:
    // `moves`: PipelineInfo::joint_moves (a joint that does not move is pinned: its mean position over the
    // valid range [first, last), zero velocity and acceleration; its Coulomb velocity is still estimated).
    StreamedJacobiStates(const LogColumns& log, JacobiKernels kernels, const std::vector<bool>& moves, std::size_t first, std::size_t last);
    std::size_t samples() const override { return n_; }
    bool has_coulomb_velocity() const override { return !kernels_.coulomb.empty(); }
    const std::vector<double>& torque_fir() const override { return kernels_.torque; }
    void load(std::size_t from, std::size_t to, StateWindow& window, const ParallelForOptions& pool) const override;

private:
    const LogColumns& log_;
    JacobiKernels kernels_;
    std::size_t n_ = 0;
    std::vector<bool> pinned_;
    std::vector<double> mean_;                         // pinned joints' position
    std::vector<double> coulomb_first_, coulomb_last_;  // per joint, the Coulomb velocity's first and last valid outputs (held at the ends)
};

}  // namespace jacobid::identify
