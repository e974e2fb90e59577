// SPDX-License-Identifier: MIT
#include "identify/pipeline/pipeline_fold.hpp"

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
using Lowpass = signal::ButterworthSos;

// One fold: the set-up (chunk geometry, column slots, the Coulomb columns' filter), then per chunk its stages
// (regressor, Coulomb columns, F_p, the filtered torque to the sink, rows into the factors, rows kept), then the
// factors. Work is split over threads (settings.threads) in three stages per chunk: the regressor by sample
// ranges, F_p by columns, the running QR by joints. Each piece of arithmetic is the same whatever the thread
// count (no sum is split), so the result is identical bit for bit.
class PipelineFold {
public:
    PipelineFold(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& s, PipelineInfo planned, const StateSource& states,
                 RowSink* sink);
    PipelineOutput run();

private:
    // The samples of one chunk: kept [c0, c1), estimated with F_p's margin [e0, e1), and the Coulomb filter's
    // reach around that [x0, x1).
    struct Chunk {
        std::size_t c0 = 0, c1 = 0, e0 = 0, e1 = 0, x0 = 0, x1 = 0;
        std::size_t reach = 0;  // the Coulomb columns' filter half-width: x0 = e0 - reach, x1 = e1 + reach (within the log)
        std::size_t len() const { return e1 - e0; }
        std::size_t xlen() const { return x1 - x0; }
    };
    struct SlottedEntry {
        std::size_t entry;  // in D's storage
        double* column;     // the chunk's samples of its column
    };
    struct UnslottedEntry {
        std::size_t entry, column;
    };

    std::size_t column_of(std::size_t joint, std::size_t parameter) const { return joint * static_cast<std::size_t>(c_ + 1) + parameter; }
    void run_or_rethrow(std::size_t jobs, const std::function<void(std::size_t)>& job) const;
    void set_up_chunks();
    void set_up_columns();
    void probe_column_slots();
    void set_up_coulomb();
    Chunk chunk_at(std::size_t c0) const;
    void fold_chunk(const Chunk& k);
    void load_state(std::size_t k, const std::vector<std::vector<double>>& qd, std::vector<double>& qs, std::vector<double>& qds,
                    std::vector<double>& qdds) const;
    void map_entries();
    void write_regressor(const Chunk& k, std::size_t ranges);
    void write_coulomb_columns(const Chunk& k, std::size_t ranges);
    bool give_found_columns_slots();
    void filter_columns(std::size_t len);
    void hand_filtered_torque(const Chunk& k);
    void add_rows(const Chunk& k, std::size_t first_kept);
    void keep_rows(const Chunk& k, std::size_t first_kept);
    void report_progress(std::size_t c1);
    PipelineOutput finish();

    const robot::RobotModel& model_;
    const LogColumns& log_;
    const PipelineSettings& s_;
    const StateSource& states_;
    RowSink* sink_;
    PipelineOutput out_;
    PipelineInfo& info_;
    const int joints_, c_;
    const int threads_;
    ParallelForOptions pool_;
    // Columns with memory (presliding friction): their state integrated once along the whole log's raw
    // positions, then written into every row before F_p, so they are filtered and decimated like the rest.
    std::size_t history_size_ = 0;
    std::vector<double> history_;
    Lowpass fp_{};
    std::size_t margin_ = 0, a0_ = 0, a1_ = 0, keep0_ = 0, keep1_ = 0, d_ = 1, chunk_ = 0;
    std::vector<RunningQr> qr_;
    std::vector<LaggedProducts> lagged_;  // residual autocorrelation, for the std (residual_correlation.hpp)
    std::size_t columns_ = 0;
    ChunkColumns buffer_{0};
    std::vector<std::vector<double>> workspaces_;
    std::vector<signal::InterleavedFiltfilt> lane_filters_;
    std::vector<char> column_used_;
    std::vector<std::vector<char>> unslotted_nonzero_;  // per regressor range: the columns without a slot found nonzero
    std::vector<std::size_t> used_columns_;
    StateWindow window_;  // the estimates of the chunk's samples (and of the Coulomb filter's reach around them)
    std::vector<int> coulomb_columns_;  // RobotModel::coulomb_column_indices, when their velocity is given (StateEstimates::qd_coulomb)
    std::vector<std::vector<double>> coulomb_raw_;
    std::size_t full_length_ = 0;
    Lowpass coulomb_fq_{};
    std::vector<double> row_;
    DecimatedRow decimated_;
    std::vector<const double*> torque_piece_;
    double regressor_seconds_ = 0.0, ls_seconds_ = 0.0;
    int reported_tenth_ = 0;
    std::vector<SlottedEntry> slotted_;
    std::vector<UnslottedEntry> unslotted_;
};

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

// One sample's state for a regressor call, with the velocity from `qd` (window.qd, or the Coulomb columns' own).
void PipelineFold::load_state(std::size_t k, const std::vector<std::vector<double>>& qd, std::vector<double>& qs, std::vector<double>& qds,
                              std::vector<double>& qdds) const {
    const std::size_t i = k - window_.from;
    for (std::size_t j = 0; j < qs.size(); ++j) {
        qs[j] = window_.q[j][i];
        qds[j] = qd[j][i];
        qdds[j] = window_.qdd[j][i];
    }
}

// Where each entry of a sample's regressor D goes, worked out once per chunk rather than per entry (6 x 52
// branches per sample; without them, 5.4 % fewer instructions for a PUMA log, callgrind): the columns with a
// slot are copied, the others only checked for a first nonzero value.
void PipelineFold::map_entries() {
    slotted_.clear();
    unslotted_.clear();
    for (int j = 0; j < joints_; ++j) {
        for (int p = 0; p < c_; ++p) {
            const std::size_t col = column_of(static_cast<std::size_t>(j), static_cast<std::size_t>(p));
            const auto entry = static_cast<std::size_t>(p) * static_cast<std::size_t>(joints_) + static_cast<std::size_t>(j);  // D is column-major
            if (double* x = buffer_[col]) {
                slotted_.push_back({entry, x});
            } else {
                unslotted_.push_back({entry, col});
            }
        }
    }
}

void PipelineFold::write_regressor(const Chunk& k, std::size_t ranges) {
    const std::size_t len = k.len();
    run_or_rethrow(ranges, [&](std::size_t range) {
        Eigen::MatrixXd D(joints_, c_);
        std::vector<double> qs(static_cast<std::size_t>(joints_)), qds(qs), qdds(qs);
        for (std::size_t i = len * range / ranges; i < len * (range + 1) / ranges; ++i) {
            const std::size_t sample = k.e0 + i;
            load_state(sample, window_.qd, qs, qds, qdds);
            model_.regressor(qs.data(), qds.data(), qdds.data(), D);
            if (history_size_ > 0) model_.history_columns(history_.data() + sample * history_size_, D);
            const double* entries = D.data();
            for (const SlottedEntry& e : slotted_) e.column[i] = entries[e.entry];
            for (const UnslottedEntry& e : unslotted_) {
                if (entries[e.entry] != 0.0) unslotted_nonzero_[range][e.column] = 1;
            }
            for (int j = 0; j < joints_; ++j) {
                buffer_[column_of(static_cast<std::size_t>(j), static_cast<std::size_t>(c_))][i] = window_.tau[static_cast<std::size_t>(j)][sample - window_.from];
            }
        }
    });
}

// The Coulomb columns s(alpha qd) on the wider velocity, then through the torque's own filter
// (StateEstimates::qd_coulomb), on [e0, e1) plus the filter's reach on each side. Storage only where the
// column has a slot (a Coulomb column is zero outside its own joint's row); a nonzero value elsewhere gives
// it one, as in the regressor.
void PipelineFold::write_coulomb_columns(const Chunk& k, std::size_t ranges) {
    const std::size_t xlen = k.xlen();
    const auto coulomb_column_of = [&](std::size_t ci, std::size_t j) { return column_of(j, static_cast<std::size_t>(coulomb_columns_[ci])); };
    for (std::size_t ci = 0; ci < coulomb_columns_.size(); ++ci) {
        for (std::size_t j = 0; j < static_cast<std::size_t>(joints_); ++j) {
            auto& raw = coulomb_raw_[ci * static_cast<std::size_t>(joints_) + j];
            if (buffer_.has(coulomb_column_of(ci, j))) {
                raw.resize(xlen);
            } else {
                std::vector<double>().swap(raw);
            }
        }
    }
    // The Coulomb columns evaluated again per sample (RobotModel::coulomb_columns: alone for the serial
    // models, the whole regressor otherwise), split by sample ranges over the threads like the regressor.
    run_or_rethrow(ranges, [&](std::size_t range) {
        Eigen::MatrixXd D(joints_, c_);
        std::vector<double> qs(static_cast<std::size_t>(joints_)), qds(qs), qdds(qs);
        for (std::size_t sample = k.x0 + xlen * range / ranges; sample < k.x0 + xlen * (range + 1) / ranges; ++sample) {
            load_state(sample, window_.qd_coulomb, qs, qds, qdds);
            model_.coulomb_columns(qs.data(), qds.data(), qdds.data(), D);
            for (std::size_t ci = 0; ci < coulomb_columns_.size(); ++ci) {
                for (int j = 0; j < joints_; ++j) {
                    auto& raw = coulomb_raw_[ci * static_cast<std::size_t>(joints_) + static_cast<std::size_t>(j)];
                    const double value = D(j, coulomb_columns_[ci]);
                    if (!raw.empty()) {
                        raw[sample - k.x0] = value;
                    } else if (value != 0.0) {
                        unslotted_nonzero_[range][coulomb_column_of(ci, static_cast<std::size_t>(j))] = 1;
                    }
                }
            }
        }
    });
    const std::vector<double>& torque_fir = states_.torque_fir();
    const bool fir = !torque_fir.empty();
    std::vector<double> filtered(xlen);
    for (std::size_t ci = 0; ci < coulomb_columns_.size(); ++ci) {
        for (int j = 0; j < joints_; ++j) {
            const auto& raw = coulomb_raw_[ci * static_cast<std::size_t>(joints_) + static_cast<std::size_t>(j)];
            double* target = buffer_[coulomb_column_of(ci, static_cast<std::size_t>(j))];
            // A filter of zeros is zeros (and a column without a slot has no raw values: it held none).
            if (std::all_of(raw.begin(), raw.end(), [](double v) { return v == 0.0; })) {
                if (target) std::fill(target, target + k.len(), 0.0);
                continue;
            }
            std::size_t shift = 0;  // filtered[m] belongs to sample x0 + m + shift
            if (fir) {
                const BatchStatus status = signal::differentiate_batch(Span<const double>(torque_fir), Span<const double>(raw),
                                                                       Span<double>(filtered.data(), xlen - torque_fir.size() + 1));
                if (status != BatchStatus::Ok) throw InputError(fmt::format("{}: {}", log_.source, describe(status)));
                shift = k.reach;
            } else {
                signal::filtfilt_or_throw(coulomb_fq_, raw.data(), filtered.data(), xlen, workspaces_[0]);
            }
            for (std::size_t sample = k.e0; sample < k.e1; ++sample) target[sample - k.e0] = filtered[sample - k.x0 - shift];
        }
    }
}

// The columns found nonzero without a slot get one; true when any did (the chunk is then written again).
bool PipelineFold::give_found_columns_slots() {
    bool added = false;
    for (auto& found : unslotted_nonzero_) {
        for (std::size_t col = 0; col < columns_; ++col) {
            if (!found[col]) continue;
            found[col] = 0;
            buffer_.add(col);
            added = true;
        }
    }
    return added;
}

// F_p on every column that holds anything (a column of zeros, e.g. a link's parameter in an earlier
// joint's row, filters to zeros and stays as the regressor wrote it), kFiltfiltLanes columns at a
// time (interleaved_filtfilt.hpp: each column's numbers are sosfiltfilt's, whatever its block).
void PipelineFold::filter_columns(std::size_t len) {
    const auto ranges = static_cast<std::size_t>(threads_);
    run_or_rethrow(ranges, [&](std::size_t t) {
        for (std::size_t col = t; col < columns_; col += ranges) {
            const double* x = buffer_[col];
            column_used_[col] = x != nullptr && std::any_of(x, x + len, [](double v) { return v != 0.0; });
        }
    });
    used_columns_.clear();
    for (std::size_t col = 0; col < columns_; ++col) {
        if (column_used_[col]) used_columns_.push_back(col);
    }
    const std::size_t blocks = (used_columns_.size() + signal::kFiltfiltLanes - 1) / signal::kFiltfiltLanes;
    run_or_rethrow(ranges, [&](std::size_t t) {
        std::array<double*, signal::kFiltfiltLanes> signals{};
        for (std::size_t b = t; b < blocks; b += ranges) {
            const std::size_t from = b * signal::kFiltfiltLanes;
            const std::size_t count = std::min(signal::kFiltfiltLanes, used_columns_.size() - from);
            for (std::size_t l = 0; l < count; ++l) signals[l] = buffer_[used_columns_[from + l]];
            lane_filters_[t].filter_in_place(signals.data(), count, len);
        }
    });
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

}  // namespace

PipelineOutput fold_source(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& s, PipelineInfo planned,
                           const StateSource& states, RowSink* sink) {
    return PipelineFold(model, log, s, std::move(planned), states, sink).run();
}

}  // namespace jacobid::identify
