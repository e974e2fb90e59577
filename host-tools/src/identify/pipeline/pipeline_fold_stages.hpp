// SPDX-License-Identifier: MIT
#pragma once
// The fold's stages (pipeline_fold.hpp fold_source), shared by its two sources: pipeline_fold.cpp (set-up, the
// chunk loop, the rows into the factors) and pipeline_fold_columns.cpp (each chunk's columns: regressor, Coulomb
// columns, F_p). Internal to identify/pipeline/.
#include <cstddef>
#include <functional>
#include <vector>

#include "core/parallel_for.hpp"
#include "identify/pipeline/chunk_columns.hpp"
#include "identify/pipeline/pipeline.hpp"
#include "identify/pipeline/running_qr.hpp"
#include "identify/pipeline/state_source.hpp"
#include "identify/solve/residual_correlation.hpp"
#include "robot/robot_model.hpp"
#include "signal/baseline_response.hpp"
#include "signal/interleaved_filtfilt.hpp"

namespace jacobid::identify {

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
    signal::ButterworthSos fp_{};
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
    signal::ButterworthSos coulomb_fq_{};
    std::vector<double> row_;
    DecimatedRow decimated_;
    std::vector<const double*> torque_piece_;
    double regressor_seconds_ = 0.0, ls_seconds_ = 0.0;
    int reported_tenth_ = 0;
    std::vector<SlottedEntry> slotted_;
    std::vector<UnslottedEntry> unslotted_;
};

}  // namespace jacobid::identify
