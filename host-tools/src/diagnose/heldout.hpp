// SPDX-License-Identifier: MIT
#pragma once
// Error on data a model was not fitted on: the validation log's rows when there is one, otherwise blocked
// cross-validation (each contiguous time block predicted by the fit on the others; contiguous blocks keep
// the correlated neighbours of a held-out row out of its fit).
#include <vector>

#include "diagnose/blocked_grams.hpp"

namespace jacobid::diagnose {

class HeldOut {
public:
    // weight2: squared per-joint row weights of the fit (1 / sigma_j^2).
    HeldOut(const BlockedGrams& train, const BlockedGrams* validation, std::vector<double> weight2)
        : train_(train), validation_(validation), weight2_(std::move(weight2)) {}
    // RMS prediction error of the weighted fit over `columns`: combined over joints in weighted units
    // (joint < 0) or in N.m for one joint. NaN when a fit is singular.
    double rms(const std::vector<int>& columns, int joint = -1) const;
    bool uses_validation() const { return validation_ != nullptr; }

private:
    const BlockedGrams& train_;
    const BlockedGrams* validation_;
    std::vector<double> weight2_;
};

}  // namespace jacobid::diagnose
