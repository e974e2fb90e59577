// SPDX-License-Identifier: MIT
#include "io/candump_joints.hpp"

#include <fmt/core.h>

#include <cmath>

#include "core/errors.hpp"

namespace jacobid::io {
namespace {

// One single-joint decoder set per joint: dispatching to each tells which joint a frame belongs to, which
// the multi-joint set does not report.
using OneJoint = hal::JointDecoderSet<1>;

// Where one sample's frames lie in the capture: a sample whose frames spread over more than half the time
// to its neighbour sample joined two controller cycles, which is what a lost frame of the joint that
// came first does (the joint's next-cycle frame completes the cycle, every later sample is shifted).
struct SampleSpan {
    std::int64_t first_ns = 0, last_ns = 0;
    std::size_t first_line = 0, last_line = 0;
    std::size_t last_joint = 0;  // the joint whose frame came last (the one whose previous frame is missing)
};

void require_one_cycle_per_sample(const std::vector<SampleSpan>& spans, const std::string& source) {
    if (spans.size() < 2) return;
    for (std::size_t k = 0; k < spans.size(); ++k) {
        const SampleSpan& s = spans[k];
        // Differences exact in int64 (a capture's epoch is ~1.7e18 ns, beyond a double's integers), infinite
        // where time stamps near the int64 range (a capture may hold any) would overflow them.
        auto ns_between = [](std::int64_t later, std::int64_t earlier) {
            std::int64_t d = 0;
            if (__builtin_sub_overflow(later, earlier, &d)) return later > earlier ? HUGE_VAL : -HUGE_VAL;
            return static_cast<double>(d);
        };
        const double to_neighbour =
            std::abs(k + 1 < spans.size() ? ns_between(spans[k + 1].first_ns, s.first_ns) : ns_between(s.first_ns, spans[k - 1].first_ns));
        const double spread = ns_between(s.last_ns, s.first_ns);
        if (spread > 0 && 2 * spread > to_neighbour) {
            throw InputError(fmt::format("{}:{}: the frame of joint {} is {:g} ms after the cycle that began on line {}, and the next cycle "
                                         "begins {:g} ms after that one: joint {}'s frame of the cycle of line {} was lost (the following "
                                         "samples would be shifted by a cycle)",
                                         source, s.last_line, s.last_joint + 1, spread * 1e-6, s.first_line, to_neighbour * 1e-6, s.last_joint + 1, s.first_line));
        }
    }
}

// The samples' times (s from the first) onto the uniform grid they jitter around, fitted by least squares
// over the sample index; InputError naming the line where they are not increasing or stray too far.
void regrid_cycle_times(std::vector<double>& t, const std::vector<SampleSpan>& spans, const std::string& source, CandumpJointCounts& c) {
    const std::size_t n = t.size();
    for (std::size_t k = 1; k < n; ++k) {
        if (!(t[k] > t[k - 1])) {
            throw InputError(fmt::format("{}:{}: the cycle beginning on this line is stamped {:.6f} s, not after {:.6f} s of the cycle on line {} "
                                         "(time must increase)",
                                         source, spans[k].first_line, t[k], t[k - 1], spans[k - 1].first_line));
        }
    }
    if (n < 3) return;
    double mean_k = 0.0, mean_t = 0.0;
    for (std::size_t k = 0; k < n; ++k) mean_k += static_cast<double>(k), mean_t += t[k];
    mean_k /= static_cast<double>(n), mean_t /= static_cast<double>(n);
    double skt = 0.0, skk = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        const double dk = static_cast<double>(k) - mean_k;
        skt += dk * (t[k] - mean_t), skk += dk * dk;
    }
    const double cycle = skt / skk, start = mean_t - cycle * mean_k;
    std::size_t worst = 0;
    double max_jitter = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        const double r = std::abs(t[k] - (start + cycle * static_cast<double>(k)));
        if (r > max_jitter) max_jitter = r, worst = k;
    }
    if (max_jitter > kCycleJitterTolerance * cycle) {
        std::size_t widest = 1;
        for (std::size_t k = 2; k < n; ++k) widest = t[k] - t[k - 1] > t[widest] - t[widest - 1] ? k : widest;
        const double step = t[widest] - t[widest - 1];
        const std::size_t at = step > 1.5 * cycle ? widest : worst;
        throw InputError(fmt::format("{}:{}: the cycle beginning on this line is {:.4g} ms off the uniform {:.4g} ms grid of the capture's "
                                     "stamps{} (receive-time jitter up to +-{:g} cycle is accepted): a lost cycle, a gap or a clock jump",
                                     source, spans[at].first_line, 1e3 * (t[at] - (start + cycle * static_cast<double>(at))), 1e3 * cycle,
                                     at == widest ? fmt::format(", {:.4g} ms after the cycle on line {}", 1e3 * step, spans[at - 1].first_line) : "",
                                     kCycleJitterTolerance));
    }
    // The controller's nominal cycle: the fit rounded to candump's stamp resolution of 1 us when that moves
    // it by less than 1e-4 (the fit of a 1 ms cycle under +-0.3 ms jitter is off by ~1 ns, which would scale
    // inertias by ~2e-6); a cycle of no whole number of microseconds (333.33 us) keeps the fit.
    const double rounded = std::round(cycle * 1e6) * 1e-6;
    const double nominal = std::abs(rounded - cycle) < 1e-4 * cycle ? rounded : cycle;
    c.cycle = nominal;
    c.max_jitter = max_jitter;
    c.regridded = max_jitter > 1e-3 * cycle;
    if (c.regridded) {
        for (std::size_t k = 0; k < n; ++k) t[k] = nominal * static_cast<double>(k);
    }
}

}  // namespace

CsvTable candump_joint_table(const std::vector<CandumpRecord>& records, const std::vector<hal::ProfileConfig>& joints,
                             const std::vector<std::string>& position_columns, const std::vector<std::string>& torque_columns,
                             const std::string& time_column, const std::string& source, CandumpJointCounts* counts) {
    const std::size_t n = joints.size();
    if (n == 0 || position_columns.size() != n || torque_columns.size() != n) {
        throw InputError(fmt::format("{}: {} CAN joints but {} position and {} torque columns", source, n, position_columns.size(),
                                     torque_columns.size()));
    }
    std::vector<OneJoint> decoders(n);
    for (std::size_t j = 0; j < n; ++j) {
        const hal::DecoderSetConfigResult r = decoders[j].configure(Span<const hal::ProfileConfig>(&joints[j], 1));
        if (r.status != hal::ConfigStatus::Ok) throw InputError(fmt::format("{}: joint {}: {}", source, j + 1, hal::describe(r.status)));
        decoders[j].begin_cycle();
    }
    std::vector<std::string> header{time_column};
    header.insert(header.end(), position_columns.begin(), position_columns.end());
    header.insert(header.end(), torque_columns.begin(), torque_columns.end());
    CsvTable table(source, header);
    CandumpJointCounts c;
    std::vector<bool> has_position(n, false), has_torque(n, false);
    std::vector<std::size_t> first_line(n, 0);
    std::size_t complete = 0;
    std::int64_t cycle_time = 0, first_time = 0;
    bool cycle_open = false;
    SampleSpan span;
    std::vector<SampleSpan> spans;
    for (const CandumpRecord& rec : records) {
        if (rec.frame.error()) {
            ++c.error_frames;
            continue;
        }
        std::size_t owner = n;
        hal::DecodeStatus status = hal::DecodeStatus::UnknownId;
        bool position_before = false, torque_before = false;
        for (std::size_t j = 0; j < n && owner == n; ++j) {
            position_before = decoders[j].state(0).position_fresh;
            torque_before = decoders[j].state(0).torque_fresh;
            const std::int64_t position_time = decoders[j].state(0).position_time_ns;
            const std::int64_t torque_time = decoders[j].state(0).torque_time_ns;
            status = decoders[j].dispatch(rec.frame);
            if (status == hal::DecodeStatus::UnknownId) continue;
            owner = j;
            if (status != hal::DecodeStatus::Ok) {
                throw InputError(fmt::format("{}:{}: frame 0x{:X} of joint {}: {}", source, rec.line, rec.frame.id, j + 1, hal::describe(status)));
            }
            const hal::JointState& s = decoders[j].state(0);
            const bool position_now = s.position_fresh && (!position_before || s.position_time_ns != position_time);
            const bool torque_now = s.torque_fresh && (!torque_before || s.torque_time_ns != torque_time);
            if ((position_now && has_position[j]) || (torque_now && has_torque[j])) {
                std::string missing;
                for (std::size_t k = 0; k < n; ++k) {
                    if (!(has_position[k] && has_torque[k])) missing += (missing.empty() ? "" : ", ") + std::to_string(k + 1);
                }
                throw InputError(fmt::format("{}:{}: joint {} sends again (its previous frame is on line {}) before joint(s) {} completed the "
                                             "cycle: a frame was lost or the capture is incomplete",
                                             source, rec.line, j + 1, first_line[j], missing));
            }
            if (!cycle_open) {
                cycle_open = true;
                cycle_time = rec.frame.timestamp_ns;
                span = SampleSpan{cycle_time, cycle_time, rec.line, rec.line, j};
            }
            if (rec.frame.timestamp_ns >= span.last_ns) span = SampleSpan{span.first_ns, rec.frame.timestamp_ns, span.first_line, rec.line, j};
            if (!has_position[j] && !has_torque[j]) first_line[j] = rec.line;
            has_position[j] = has_position[j] || position_now;
            has_torque[j] = has_torque[j] || torque_now;
        }
        if (owner == n) {
            ++c.frames_other_ids;
            continue;
        }
        ++c.frames_decoded;
        complete = 0;
        for (std::size_t j = 0; j < n; ++j) complete += (has_position[j] && has_torque[j]) ? 1 : 0;
        if (complete < n) continue;
        if (c.samples == 0) first_time = cycle_time;
        table.mutable_column(0).push_back(static_cast<double>(cycle_time - first_time) * 1e-9);
        for (std::size_t j = 0; j < n; ++j) {
            table.mutable_column(1 + j).push_back(decoders[j].state(0).position);
            table.mutable_column(1 + n + j).push_back(decoders[j].state(0).torque);
            decoders[j].begin_cycle();
            has_position[j] = has_torque[j] = false;
        }
        cycle_open = false;
        spans.push_back(span);
        ++c.samples;
    }
    require_one_cycle_per_sample(spans, source);
    regrid_cycle_times(table.mutable_column(0), spans, source, c);
    if (cycle_open) {
        // An incomplete last cycle (the capture stopped mid-cycle) is reported, not turned into a sample.
        fmt::print(stderr, "{}: the last cycle is incomplete ({} of {} joints) and is not used\n", source, complete, n);
    }
    if (counts) *counts = c;
    return table;
}

std::string format_candump_line(const hal::CanFrame& f, const std::string& interface) {
    const std::int64_t seconds = f.timestamp_ns / 1'000'000'000;
    const std::int64_t micros = (f.timestamp_ns % 1'000'000'000) / 1000;
    std::string line = fmt::format("({}.{:06}) {} ", seconds, micros, interface);
    line += f.extended() ? fmt::format("{:08X}", f.id) : fmt::format("{:03X}", f.id);
    if (f.fd()) {
        // candump's FD flags digit: bit 0 bit-rate switch, bit 1 error state indicator.
        const int fd_flags = ((f.flags & hal::kCanBitRateSwitch) ? 1 : 0) | ((f.flags & hal::kCanErrorStateIndicator) ? 2 : 0);
        line += fmt::format("##{:X}", fd_flags);
    } else {
        line += "#";
    }
    if (f.remote()) return line + "R";
    for (std::size_t i = 0; i < f.len; ++i) line += fmt::format("{:02X}", f.data[i]);
    return line;
}

}  // namespace jacobid::io
