// SPDX-License-Identifier: MIT
#include "identify/pipeline/pipeline_fold.hpp"

#include "identify/pipeline/pipeline_fold_stages.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <utility>

#include "core/errors.hpp"
#include "core/free_memory.hpp"
#include "core/parallel_for.hpp"
#include "identify/pipeline/chunk_columns.hpp"
#include "identify/solve/residual_correlation.hpp"
#include "identify/pipeline/running_qr.hpp"
#include "signal/baseline_response.hpp"
#include "signal/fft_convolver.hpp"
#include "signal/interleaved_filtfilt.hpp"
#include "signal/kernel_design_checked.hpp"

namespace jacobid::identify {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace


PipelineFold::PipelineFold(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& s, PipelineInfo planned,
                           const StateSource& states, RowSink* sink)
    : model_(model), log_(log), s_(s), states_(states), sink_(sink), info_(out_.info), joints_(model.joint_count()), c_(model.parameter_count()),
      threads_(std::max(1, s.threads)) {
    out_.info = std::move(planned);
    pool_.threads = threads_;
    history_size_ = static_cast<std::size_t>(model.history_size());
    model.integrate_history(log.q, history_);
    set_up_chunks();
    set_up_columns();
    set_up_coulomb();
}

void PipelineFold::run_or_rethrow(std::size_t jobs, const std::function<void(std::size_t)>& job) const {
    for (const auto& error : parallel_for(jobs, pool_, job)) {
        if (error) std::rethrow_exception(error);
    }
}

void PipelineFold::set_up_chunks() {
    const double fs = 1.0 / log_.sample_period;
    fp_ = signal::design_butterworth_or_throw(s_.decimation_order, info_.decimation_cutoff, log_.sample_period, "decimation filter F_p");
    // Margin: F_p's impulse response decays as exp(-0.38 * 2 pi fc t) for order 4 (slowest pole); 16 / fc
    // seconds bring a chunk boundary's transient below 1e-16 whatever the order up to 16.
    margin_ = static_cast<std::size_t>(std::ceil(16.0 * fs / info_.decimation_cutoff * std::max(1.0, s_.decimation_order / 4.0)));
    a0_ = info_.first;
    a1_ = info_.last;
    keep0_ = a0_ + info_.crop;
    keep1_ = a1_ - info_.crop;
    if (s_.kept_to > s_.kept_from) {
        if (s_.kept_from < keep0_ || s_.kept_to > keep1_) {
            throw InputError(fmt::format("{}: the samples to keep [{}, {}) reach into the differentiator and F_p transients (valid [{}, {}))",
                                         log_.source, s_.kept_from, s_.kept_to, keep0_, keep1_));
        }
        keep0_ = s_.kept_from;
        keep1_ = s_.kept_to;
    }
    d_ = static_cast<std::size_t>(info_.decimation);
    chunk_ = std::max(s_.chunk, 4 * margin_);
}

void PipelineFold::set_up_columns() {
    for (int j = 0; j < joints_; ++j) {
        qr_.emplace_back(c_ + 1);
        lagged_.emplace_back(c_ + 1, s_.residual_lags);
    }
    columns_ = static_cast<std::size_t>(joints_) * static_cast<std::size_t>(c_ + 1);
    return_freed_memory();  // the set-up's whole-log temporaries, before the fold's own buffers
    buffer_ = ChunkColumns(columns_);
    for (int j = 0; j < joints_; ++j) buffer_.add(column_of(static_cast<std::size_t>(j), static_cast<std::size_t>(c_)));
    probe_column_slots();
    workspaces_.resize(static_cast<std::size_t>(threads_));
    lane_filters_.assign(static_cast<std::size_t>(threads_), signal::InterleavedFiltfilt(fp_));
    column_used_.resize(columns_);
    unslotted_nonzero_.assign(static_cast<std::size_t>(threads_), std::vector<char>(columns_, 0));
    row_.resize(static_cast<std::size_t>(c_ + 1));
    out_.plot.y.resize(static_cast<std::size_t>(joints_));
    out_.plot.w.resize(static_cast<std::size_t>(joints_));
    torque_piece_.resize(static_cast<std::size_t>(joints_));
    if (sink_) {
        decimated_.w.resize(joints_, c_);
        decimated_.y.resize(joints_);
        decimated_.q.resize(joints_);
        decimated_.qd.resize(joints_);
        decimated_.qdd.resize(joints_);
    }
}

// The columns that hold a value at a few arbitrary states get their slots now, so that the first chunk
// is not written twice (a short log is one or two chunks); a column found later gets its slot then.
void PipelineFold::probe_column_slots() {
    Eigen::MatrixXd D(joints_, c_);
    std::vector<double> qs(static_cast<std::size_t>(joints_)), qds(qs), qdds(qs), state(history_size_, 0.5);
    for (int probe = 0; probe < 3; ++probe) {
        for (int j = 0; j < joints_; ++j) {
            qs[static_cast<std::size_t>(j)] = 0.37 + 1.13 * probe + 0.71 * j;
            qds[static_cast<std::size_t>(j)] = 0.9 - 0.53 * probe + 0.29 * j;
            qdds[static_cast<std::size_t>(j)] = -1.7 + 0.83 * probe + 0.47 * j;
        }
        model_.regressor(qs.data(), qds.data(), qdds.data(), D);
        if (history_size_ > 0) model_.history_columns(state.data(), D);
        for (int j = 0; j < joints_; ++j) {
            for (int p = 0; p < c_; ++p) {
                if (D(j, p) != 0.0) buffer_.add(column_of(static_cast<std::size_t>(j), static_cast<std::size_t>(p)));
            }
        }
    }
}

void PipelineFold::set_up_coulomb() {
    full_length_ = states_.samples();
    if (!states_.has_coulomb_velocity()) return;
    coulomb_columns_ = model_.coulomb_column_indices();
    coulomb_raw_.resize(coulomb_columns_.size() * static_cast<std::size_t>(joints_));
    if (states_.torque_fir().empty()) {
        coulomb_fq_ = signal::design_butterworth_or_throw(s_.butterworth_order, info_.prefilter_cutoff, log_.sample_period, "Butterworth prefilter");
    }
}

PipelineFold::Chunk PipelineFold::chunk_at(std::size_t c0) const {
    Chunk k;
    k.c0 = c0;
    k.c1 = std::min(keep1_, c0 + chunk_);
    k.e0 = c0 >= a0_ + margin_ ? c0 - margin_ : a0_;
    k.e1 = std::min(a1_, k.c1 + margin_);
    // The Coulomb columns are filtered like the torque: their estimates reach `reach` samples further.
    const std::vector<double>& torque_fir = states_.torque_fir();
    k.reach = coulomb_columns_.empty() ? 0 : !torque_fir.empty() ? (torque_fir.size() - 1) / 2 : info_.first;
    k.x0 = k.e0 >= k.reach ? k.e0 - k.reach : 0;
    k.x1 = std::min(full_length_, k.e1 + k.reach);
    return k;
}

PipelineOutput PipelineFold::run() {
    // Decimated samples are k = a0 + m d; the first kept one is the first such k >= keep0.
    for (std::size_t c0 = keep0_; c0 < keep1_; c0 += chunk_) fold_chunk(chunk_at(c0));
    return finish();
}

void PipelineFold::fold_chunk(const Chunk& k) {
    const auto t0 = Clock::now();
    states_.load(k.x0, k.x1, window_, pool_);
    const auto ranges = static_cast<std::size_t>(threads_);
    const std::size_t regressor_ranges = model_.concurrent_regressor() ? ranges : 1;
    // The chunk's columns are written again when one of them holds its first nonzero value (it then
    // gets a slot): rarely, the probe has given most of them theirs.
    for (bool slots_added = true; slots_added;) {
        buffer_.fit(k.len());
        map_entries();
        write_regressor(k, regressor_ranges);
        if (!coulomb_columns_.empty()) write_coulomb_columns(k, regressor_ranges);
        slots_added = give_found_columns_slots();
    }
    filter_columns(k.len());
    const auto t1 = Clock::now();
    regressor_seconds_ += std::chrono::duration<double>(t1 - t0).count();
    if (sink_) hand_filtered_torque(k);
    const std::size_t first_kept = k.c0 + (d_ - (k.c0 - a0_) % d_) % d_;
    add_rows(k, first_kept);
    keep_rows(k, first_kept);
    ls_seconds_ += std::chrono::duration<double>(Clock::now() - t1).count();
    report_progress(k.c1);
}

// Each chunk hands out its kept samples [c0, c1); the first chunk also its leading margin and the last its
// trailing one, which start at a0 and end at a1 (margin > crop), so the pieces tile [a0, a1) once, every
// sample taken where its chunk's transients have died out.
void PipelineFold::hand_filtered_torque(const Chunk& k) {
    const std::size_t lo = k.c0 == keep0_ ? k.e0 : k.c0, hi = k.c1 == keep1_ ? k.e1 : k.c1;
    for (int j = 0; j < joints_; ++j) {
        torque_piece_[static_cast<std::size_t>(j)] = buffer_[column_of(static_cast<std::size_t>(j), static_cast<std::size_t>(c_))] + (lo - k.e0);
    }
    sink_->filtered_torque(lo, hi - lo, torque_piece_);
}

// Each joint's rows into its own running QR and lagged products (one joint per job, rows in order).
void PipelineFold::add_rows(const Chunk& k, std::size_t first_kept) {
    run_or_rethrow(static_cast<std::size_t>(joints_), [&](std::size_t j) {
        std::vector<double> joint_row(static_cast<std::size_t>(c_ + 1));
        for (std::size_t sample = first_kept; sample < k.c1; sample += d_) {
            for (int p = 0; p <= c_; ++p) joint_row[static_cast<std::size_t>(p)] = buffer_.at(column_of(j, static_cast<std::size_t>(p)), sample - k.e0);
            qr_[j].add_row(joint_row.data());
            lagged_[j].add_row(joint_row.data());
        }
    });
}

// The decimated rows kept for the fit plots (up to settings.plot_rows) and handed to the sink.
void PipelineFold::keep_rows(const Chunk& k, std::size_t first_kept) {
    for (std::size_t sample = first_kept; sample < k.c1 && (sink_ || out_.plot.t.size() < s_.plot_rows); sample += d_) {
        const std::size_t i = sample - k.e0;
        const bool keep_for_plot = out_.plot.t.size() < s_.plot_rows;
        const double t = log_.start_time + static_cast<double>(sample) * log_.sample_period;
        if (keep_for_plot) out_.plot.t.push_back(t);
        for (int j = 0; j < joints_; ++j) {
            const auto js = static_cast<std::size_t>(j);
            for (int p = 0; p <= c_; ++p) row_[static_cast<std::size_t>(p)] = buffer_.at(column_of(js, static_cast<std::size_t>(p)), i);
            if (keep_for_plot) {
                out_.plot.y[js].push_back(row_[static_cast<std::size_t>(c_)]);
                out_.plot.w[js].insert(out_.plot.w[js].end(), row_.begin(), row_.end() - 1);
            }
            if (sink_) {
                for (int p = 0; p < c_; ++p) decimated_.w(j, p) = row_[static_cast<std::size_t>(p)];
                decimated_.y[j] = row_[static_cast<std::size_t>(c_)];
                decimated_.q[j] = window_.q[js][sample - window_.from];
                decimated_.qd[j] = window_.qd[js][sample - window_.from];
                decimated_.qdd[j] = window_.qdd[js][sample - window_.from];
            }
        }
        if (sink_) {
            decimated_.sample = sample;
            decimated_.t = t;
            sink_->row(decimated_);
        }
    }
}

// One line per tenth: readable in a terminal and in a CI log alike.
void PipelineFold::report_progress(std::size_t c1) {
    if (!s_.progress || keep1_ - keep0_ <= 10 * chunk_) return;
    const auto tenth = static_cast<int>(10 * (c1 - keep0_) / (keep1_ - keep0_));
    if (tenth > reported_tenth_) {
        reported_tenth_ = tenth;
        fmt::print(stderr, "identify [{}]: regressor + F_p {} %\n", to_string(s_.method), 10 * tenth);
    }
}

PipelineOutput PipelineFold::finish() {
    const auto t2 = Clock::now();
    for (auto& f : qr_) {
        out_.factors.r.push_back(f.r());
        out_.factors.rows.push_back(f.rows());
    }
    if (s_.residual_lags > 0) {
        for (auto& l : lagged_) out_.factors.lagged.push_back(l.gamma());
    }
    ls_seconds_ += std::chrono::duration<double>(Clock::now() - t2).count();
    info_.seconds_regressor_filter = regressor_seconds_;
    info_.seconds_ls = ls_seconds_;
    std::size_t equations = 0;
    for (auto r : out_.factors.rows) equations += r;
    if (s_.require_own_equations && equations <= static_cast<std::size_t>(c_)) {
        throw InputError(fmt::format("{}: only {} equations after decimation for {} parameters: the log is too short", log_.source, equations, c_));
    }
    if (s_.progress) {
        fmt::print(stderr, "identify [{}]: regressor + F_p {:.2f} s, LS {:.2f} s, {} equations\n", to_string(s_.method), regressor_seconds_,
                   ls_seconds_, equations);
    }
    return std::move(out_);
}

PipelineOutput fold_source(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& s, PipelineInfo planned,
                           const StateSource& states, RowSink* sink) {
    return PipelineFold(model, log, s, std::move(planned), states, sink).run();
}

}  // namespace jacobid::identify
