// SPDX-License-Identifier: MIT
#pragma once
// A reference given as a table (`jacobid simulate --trajectory traj.csv`, e.g. from `jacobid excite`):
// columns t, q1..qn, qd1..qn, qdd1..qn (rad, rad/s, rad/s^2), t uniform from 0. Between rows the position
// follows the quintic Hermite interpolant of (q, qd, qdd) at both rows (so q, qd and qdd stay consistent
// and continuous); after the last row the table repeats (a trajectory that ends at rest where it started,
// as excite's do, plays period after period).
#include <optional>
#include <string>
#include <vector>

#include "io/csv_table.hpp"
#include "io/position_bounds.hpp"
#include "sim/quintic_trajectory.hpp"

namespace jacobid::sim {

class TabulatedTrajectory {
public:
    // InputError naming the file, line and column for a missing column or one the robot has no joint for,
    // fewer than 2 rows, a time step outside 1 us .. 1000 s, non-uniform or non-increasing time, a table that
    // does not end where it starts (q, qd, qdd at the last row vs the first, within 1e-6) when it must repeat,
    // a position beyond `limits[j]` (nullopt: not checked), or qd, qdd that are not q's derivatives
    // (sim/reference_checks.hpp).
    TabulatedTrajectory(const io::CsvTable& table, int joints, const std::vector<std::optional<io::PositionBounds>>& limits);

    double length() const { return t_.back(); }  // s: one pass; the table repeats after it
    std::vector<double> start() const;
    void evaluate(double t, ReferenceSample& out) const;

private:
    std::vector<double> t_;
    double step_ = 0.0;
    std::vector<std::vector<double>> q_, qd_, qdd_;  // per joint
};

}  // namespace jacobid::sim
