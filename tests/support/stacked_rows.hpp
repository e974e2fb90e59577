// SPDX-License-Identifier: MIT
#pragma once
// The independent reference for stacked identification systems (--on-gap split segments, several --in
// logs): every decimated row the pipeline produces on each piece, collected through its RowSink, stacked
// into one dense system and solved by SVD in the test, never through the running QR factors under test.
#include <Eigen/Dense>
#include <vector>

#include "identify/pipeline/pipeline.hpp"

namespace jacobid::test {

// Every decimated row of the pipeline on one piece, per joint: [W_j y_j].
struct CollectedRows : identify::RowSink {
    std::vector<std::vector<double>> rows;  // joints x parameters (column-major: joint fastest), then the joints' torques
    void row(const identify::DecimatedRow& r) override {
        std::vector<double> v(r.w.data(), r.w.data() + r.w.size());
        v.insert(v.end(), r.y.data(), r.y.data() + r.y.size());
        rows.push_back(v);
    }
};

struct StackedSystem {
    Eigen::MatrixXd w;  // every piece's rows, every joint, stacked
    Eigen::VectorXd y;
    std::vector<std::size_t> rows_per_piece;  // decimated rows (per joint) of each piece
    // The ordinary least squares of the stacked rows, by SVD.
    Eigen::VectorXd solve() const { return w.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(y); }
};

// Runs the pipeline with `settings` (the plan imposed on every piece) on each piece and stacks all rows.
inline StackedSystem stack_rows(const robot::RobotModel& model, const std::vector<identify::LogColumns>& pieces,
                                const identify::PipelineSettings& settings) {
    const int joints = model.joint_count(), c = model.parameter_count();
    std::vector<std::vector<double>> all;
    StackedSystem system;
    for (const auto& piece : pieces) {
        CollectedRows rows;
        identify::run_pipeline(model, piece, settings, &rows);
        system.rows_per_piece.push_back(rows.rows.size());
        all.insert(all.end(), rows.rows.begin(), rows.rows.end());
    }
    system.w.resize(static_cast<Eigen::Index>(all.size()) * joints, c);
    system.y.resize(system.w.rows());
    for (std::size_t k = 0; k < all.size(); ++k) {
        for (int j = 0; j < joints; ++j) {
            const auto r = static_cast<Eigen::Index>(k) * joints + j;
            for (int p = 0; p < c; ++p) system.w(r, p) = all[k][static_cast<std::size_t>(p * joints + j)];
            system.y(r) = all[k][static_cast<std::size_t>(joints * c + j)];
        }
    }
    return system;
}

}  // namespace jacobid::test
