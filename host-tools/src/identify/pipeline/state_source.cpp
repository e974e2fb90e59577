// SPDX-License-Identifier: MIT
#include "identify/pipeline/state_source.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <exception>

#include "core/errors.hpp"
#include "jacobid/batch_differentiate.hpp"
#include "signal/fft_convolver.hpp"

namespace jacobid::identify {
namespace {

void resize_window(StateWindow& w, std::size_t joints, std::size_t from, std::size_t to, bool coulomb) {
    w.from = from;
    w.to = to;
    const std::size_t len = to - from;
    for (auto* columns : {&w.q, &w.qd, &w.qdd, &w.tau}) {
        columns->resize(joints);
        for (auto& c : *columns) c.resize(len);
    }
    w.qd_coulomb.resize(coulomb ? joints : 0);
    for (auto& c : w.qd_coulomb) c.resize(len);
}

void run_joints(std::size_t joints, const ParallelForOptions& pool, const std::function<void(std::size_t)>& job) {
    for (const auto& error : parallel_for(joints, pool, job)) {
        if (error) std::rethrow_exception(error);
    }
}

void copy_range(const std::vector<double>& from_column, std::size_t from, std::vector<double>& to_column) {
    std::copy(from_column.begin() + static_cast<std::ptrdiff_t>(from), from_column.begin() + static_cast<std::ptrdiff_t>(from + to_column.size()),
              to_column.begin());
}

}  // namespace

void centered_fir_range(const std::vector<double>& w, const std::vector<double>& x, std::size_t from, std::vector<double>& out, double before,
                        double after, const std::string& source) {
    const std::size_t n = x.size(), h = (w.size() - 1) / 2, to = from + out.size();
    const std::size_t k0 = std::min(std::max(from, h), to), k1 = std::max(std::min(to, n - h), k0);
    std::fill(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(k0 - from), before);
    std::fill(out.begin() + static_cast<std::ptrdiff_t>(k1 - from), out.end(), after);
    if (k0 == k1) return;
    const BatchStatus status = signal::differentiate_batch(Span<const double>(w), Span<const double>(x.data() + (k0 - h), k1 - k0 + 2 * h),
                                                           Span<double>(out.data() + (k0 - from), k1 - k0));
    if (status != BatchStatus::Ok) throw InputError(fmt::format("{}: {}", source, describe(status)));
}

void HeldStates::load(std::size_t from, std::size_t to, StateWindow& w, const ParallelForOptions& pool) const {
    const std::size_t joints = e_.q.size();
    resize_window(w, joints, from, to, has_coulomb_velocity());
    run_joints(joints, pool, [&](std::size_t j) {
        copy_range(e_.q[j], from, w.q[j]);
        copy_range(e_.qd[j], from, w.qd[j]);
        copy_range(e_.qdd[j], from, w.qdd[j]);
        copy_range(e_.tau[j], from, w.tau[j]);
        if (!w.qd_coulomb.empty()) copy_range(e_.qd_coulomb[j], from, w.qd_coulomb[j]);
    });
}

StreamedJacobiStates::StreamedJacobiStates(const LogColumns& log, JacobiKernels kernels, const std::vector<bool>& moves, std::size_t first,
                                           std::size_t last)
    : log_(log), kernels_(std::move(kernels)), n_(log.samples()) {
    const std::size_t joints = log.q.size();
    pinned_.assign(joints, false);
    mean_.assign(joints, 0.0);
    for (std::size_t j = 0; j < joints && j < moves.size(); ++j) {
        if (moves[j]) continue;
        pinned_[j] = true;
        double mean = 0.0;
        for (std::size_t k = first; k < last; ++k) mean += (*log.q[j])[k];
        mean_[j] = mean / static_cast<double>(last - first);
    }
    for (const auto* w : {&kernels_.velocity, &kernels_.acceleration, &kernels_.torque}) {
        if (w->empty() || w->size() % 2 == 0 || w->size() > n_) throw InputError(fmt::format("{}: {} samples for a {}-tap kernel", log.source, n_, w->size()));
    }
    if (!kernels_.coulomb.empty()) {
        coulomb_first_.assign(joints, 0.0);
        coulomb_last_.assign(joints, 0.0);
        for (std::size_t j = 0; j < joints; ++j) {
            const std::vector<double>& w = kernels_.coulomb[j];
            if (w.size() > n_) throw InputError(fmt::format("{}: {} samples are shorter than the Coulomb velocity kernel", log.source, n_));
            const std::size_t h = (w.size() - 1) / 2;
            std::vector<double> edge(1);
            centered_fir_range(w, *log.q[j], h, edge, 0.0, 0.0, log.source);
            coulomb_first_[j] = edge[0];
            centered_fir_range(w, *log.q[j], n_ - h - 1, edge, 0.0, 0.0, log.source);
            coulomb_last_[j] = edge[0];
        }
    }
}

void StreamedJacobiStates::load(std::size_t from, std::size_t to, StateWindow& w, const ParallelForOptions& pool) const {
    const std::size_t joints = log_.q.size();
    resize_window(w, joints, from, to, has_coulomb_velocity());
    run_joints(joints, pool, [&](std::size_t j) {
        const std::vector<double>& q = *log_.q[j];
        if (pinned_[j]) {
            std::fill(w.q[j].begin(), w.q[j].end(), mean_[j]);
            std::fill(w.qd[j].begin(), w.qd[j].end(), 0.0);
            std::fill(w.qdd[j].begin(), w.qdd[j].end(), 0.0);
        } else {
            copy_range(q, from, w.q[j]);
            centered_fir_range(kernels_.velocity, q, from, w.qd[j], 0.0, 0.0, log_.source);
            centered_fir_range(kernels_.acceleration, q, from, w.qdd[j], 0.0, 0.0, log_.source);
        }
        centered_fir_range(kernels_.torque, *log_.tau[j], from, w.tau[j], 0.0, 0.0, log_.source);
        if (!w.qd_coulomb.empty()) {
            centered_fir_range(kernels_.coulomb[j], q, from, w.qd_coulomb[j], coulomb_first_[j], coulomb_last_[j], log_.source);
        }
    });
}

}  // namespace jacobid::identify
