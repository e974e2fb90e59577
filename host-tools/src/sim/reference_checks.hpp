// SPDX-License-Identifier: MIT
#pragma once
// What a reference table (simulate --trajectory) must be before the simulator follows it: each check an
// InputError naming the file, line and column (issue 36: a 1 ns step gave a 2-row log, velocity columns that
// were not the derivative of q, a reference beyond the joint limits and a table for another robot gave exit 0).
#include <optional>
#include <vector>

#include "io/csv_table.hpp"
#include "io/position_bounds.hpp"

namespace jacobid::sim {

// The table's period bounds (s): below 1 us the table is finer than any controller samples it (a time column
// in other units); above 1000 s, as for logs (io::require_plausible_sample_period).
inline constexpr double kMinReferenceStep = 1e-6;
inline constexpr double kMaxReferenceStep = 1e3;

// Exactly t, q1..qn, qd1..qn, qdd1..qn for the robot's n joints, in any order: a missing column or one the
// simulator would not read (a column of a joint the robot does not have, any other name) is refused.
void require_reference_columns(const io::CsvTable& table, int joints);

// The time step `step` (s) of the table, between the bounds above.
void require_plausible_reference_step(const io::CsvTable& table, double step);

// Every position within the joint's limits, where the description gives them (`limits[j]`; nullopt: the
// defaults or a continuous joint, not checked). A reference is a command: unlike a log, no margin.
void require_reference_within_limits(const io::CsvTable& table, const std::vector<std::vector<double>>& q,
                                     const std::vector<std::optional<io::PositionBounds>>& limits);

// qd and qdd are q's derivatives: from each row to the next, q must move by what qd and qdd integrate to
// (h/2 (qd0 + qd1) + h^2/12 (qdd0 - qdd1), exact for quartics) and qd by what qdd integrates to (h/2 (qdd0 +
// qdd1)), within 5 % of the step's motion (a 1 kHz table of a 5 Hz sine is within 0.1 %) plus 1e-6 for
// rounded cells. Columns in other units (deg/s) or not the derivatives make the interpolated reference
// oscillate between rows.
void require_consistent_derivatives(const io::CsvTable& table, double step, const std::vector<std::vector<double>>& q,
                                    const std::vector<std::vector<double>>& qd, const std::vector<std::vector<double>>& qdd);

}  // namespace jacobid::sim
