// SPDX-License-Identifier: MIT
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/huge_pages.hpp"

namespace jacobid::identify {

// One chunk's columns (every joint's regressor columns and torque) in one block, `stride` samples apart:
// 318 vectors of 0.3 MB for a 6-axis robot were each a separate mapping that glibc returned to the kernel
// at the end of every identification, so every run faulted its 90 MB in again 4 KB at a time; one block
// is reused by every chunk and can be backed by huge pages (core/huge_pages.hpp).
// Only the columns that have held a nonzero value get a slot in the block: a serial robot's joint j row is
// zero for the parameters of the links before j and for the other joints' friction, about half of the
// PUMA 560's 318 columns (93 MB of an hour's 140 MB plateau above the log). A column without a slot reads
// as zeros, which is what the regressor wrote into it before.
class ChunkColumns {
public:
    static constexpr std::size_t kNoSlot = static_cast<std::size_t>(-1);
    explicit ChunkColumns(std::size_t columns) : slot_(columns, kNoSlot) {}
    // Gives `column` a slot; the block must be fitted again before the next write (its contents are lost).
    void add(std::size_t column) {
        if (slot_[column] == kNoSlot) slot_[column] = slots_++;
    }
    bool has(std::size_t column) const { return slot_[column] != kNoSlot; }
    // Room for `samples` per slotted column; the contents are not kept (every chunk writes its columns whole).
    void fit(std::size_t samples) {
        if (samples <= stride_ && slots_ == fitted_slots_) return;
        stride_ = std::max(stride_, samples);
        fitted_slots_ = slots_;
        storage_ = std::vector<double>();
        storage_.reserve(slots_ * stride_);
        advise_huge_pages(storage_);  // before the first write, which faults the pages in
        storage_.resize(slots_ * stride_);
    }
    // The column's samples, nullptr without a slot.
    double* operator[](std::size_t column) { return has(column) ? storage_.data() + slot_[column] * stride_ : nullptr; }
    // Sample i of the column (0 without a slot).
    double at(std::size_t column, std::size_t i) const { return has(column) ? storage_[slot_[column] * stride_ + i] : 0.0; }

private:
    std::vector<std::size_t> slot_;  // per column
    std::size_t slots_ = 0, fitted_slots_ = 0, stride_ = 0;
    std::vector<double> storage_;
};

}  // namespace jacobid::identify
