// SPDX-License-Identifier: MIT
// Each chunk's columns in the fold (pipeline_fold_stages.hpp): the regressor written sample by sample, the
// Coulomb columns on their own velocity and filter, the slots of columns found nonzero, and F_p on every
// column that holds anything.
#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "core/errors.hpp"
#include "identify/pipeline/pipeline_fold_stages.hpp"
#include "signal/fft_convolver.hpp"
#include "signal/kernel_design_checked.hpp"

namespace jacobid::identify {

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

}  // namespace jacobid::identify
