// SPDX-License-Identifier: MIT
// jacobid differentiate: velocity/acceleration (any order 0..3) of columns of a CSV log, with the Jacobi
// differentiator or the Butterworth + central Euler baseline, written with their time stamps.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>
#include <memory>
#include <optional>
#include <utility>

#include "cli/command.hpp"
#include "options/kernel_options.hpp"
#include "options/log_format_options.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"
#include "io/csv_table.hpp"
#include "io/time_axis.hpp"
#include "jacobid/frequency_response.hpp"
#include "signal/differentiation.hpp"

namespace jacobid::cli {
namespace {

struct DifferentiateOptions {
    std::string input;
    std::vector<std::string> columns;
    std::string time_column = "t";
    std::string method = "jacobi";
    std::vector<int> orders{1, 2};
    KernelOptions kernel;
    double cutoff = 0.0;
    std::string butterworth;
    double crop = -1.0;
    double time_tolerance = io::kDefaultTimeTolerance;
    std::string output = "-";
    LogFormatOptions log_format;
};

struct Channel {
    std::string name;
    signal::Estimate estimate;
};

KernelParams jacobi_params_for(const DifferentiateOptions& o, int order, double ts) {
    KernelOptions k = o.kernel;
    k.order = order;
    k.ts = ts;
    // The sample period is the log's, not an option of this command.
    KernelSource source;
    source.sample_period = fmt::format("{}: time column '{}'", o.input, o.time_column);
    if (o.cutoff > 0.0) {
        if (o.cutoff >= 0.5 / ts) {
            throw InputError(fmt::format("--cutoff {:g} Hz: must be below the log's Nyquist frequency {:g} Hz (sample period {:g} s)", o.cutoff,
                                         0.5 / ts, ts));
        }
        KernelParams base = to_kernel_params(with_overrides(k, "window=1", "--cutoff"), source);
        std::vector<double> scratch(200001);
        const WindowDesign d = window_for_cutoff(base, o.cutoff, true, Span<double>(scratch));
        if (d.status != KernelStatus::Ok) {
            throw InputError(fmt::format("--cutoff {} Hz for derivative order {}: no window fits ({})", o.cutoff, order, describe(d.status)));
        }
        k.window = d.window;
        fmt::print(stderr, "order {}: window {:.6g} s ({} taps) for a cutoff of {:.4g} Hz\n", order, d.window,
                   std::llround(d.window / ts) + 1, d.cutoff);
    }
    return to_kernel_params(k, source);
}

// The output column of derivative order n of `column`: q1_d1, or q1_filtered for order 0.
std::string channel_name(const std::string& column, int n) { return n == 0 ? column + "_filtered" : fmt::format("{}_d{}", column, n); }

// The estimates of one uniformly sampled table on the rows where every estimate exists, as CSV lines
// (time, estimates, then `marker` when not empty); `jacobi` holds the kernel of each --orders entry.
// InputError when the table is too short for the windows.
std::string estimate_rows(const io::CsvTable& table, const std::string& what, const DifferentiateOptions& o, const std::vector<KernelParams>& jacobi,
                          const std::string& marker, std::size_t& rows) {
    const io::TimeAxis time = io::check_uniform_time(table, o.time_column, o.time_tolerance);
    const double ts = time.sample_period;
    std::vector<Channel> channels;
    for (const std::string& column : o.columns) {
        const std::vector<double>& x = table.column(column);
        for (std::size_t i = 0; i < o.orders.size(); ++i) {
            const int n = o.orders[i];
            const std::string where = fmt::format("{}: column '{}'", what, column);
            const std::string name = channel_name(column, n);
            if (o.method == "jacobi") {
                channels.push_back({name, signal::jacobi_estimate(jacobi[i], x, where)});
            } else {
                const signal::ButterworthEuler bw = signal::parse_butterworth_spec(o.butterworth, "--butterworth", ts);
                const std::size_t crop = o.crop >= 0.0 ? static_cast<std::size_t>(std::llround(o.crop / ts))
                                                       : signal::butterworth_edge_samples(bw.cutoff_hz, ts);
                channels.push_back({name, signal::butterworth_euler_estimate(bw.sos, n, ts, x, crop, where)});
            }
        }
    }
    // Rows where every estimate exists, on one time grid (offsets must differ by whole samples).
    double first = -1e300, last = 1e300;
    const double frac = channels.front().estimate.first_index - std::floor(channels.front().estimate.first_index);
    for (const Channel& c : channels) {
        const double f = c.estimate.first_index - std::floor(c.estimate.first_index);
        if (std::abs(f - frac) > 1e-9) {
            throw InputError("--xi/--window: the requested estimates refer to instants that differ by a fraction of a sample; run them separately");
        }
        first = std::max(first, c.estimate.first_index);
        last = std::min(last, c.estimate.first_index + static_cast<double>(c.estimate.values.size()) - 1.0);
    }
    if (last < first) throw InputError(fmt::format("{}: the estimates have no sample in common (log too short for these windows)", what));
    std::string out;
    rows = static_cast<std::size_t>(std::llround(last - first)) + 1;
    for (std::size_t r = 0; r < rows; ++r) {
        const double index = first + static_cast<double>(r);
        out += fmt::format("{:.17g}", time.start + index * ts);
        for (const Channel& c : channels) {
            const double v = c.estimate.values[static_cast<std::size_t>(std::llround(index - c.estimate.first_index))];
            if (!std::isfinite(v)) throw InputError(fmt::format("{}: {} at t = {:.17g} s is not finite (values too large to differentiate)", what, c.name, time.start + index * ts));
            out += fmt::format(",{:.17g}", v);
        }
        out += marker.empty() ? "\n" : "," + marker + "\n";
    }
    return out;
}

// The entries (0-based) of the first value given twice, if any.
template <typename T>
std::optional<std::pair<std::size_t, std::size_t>> first_repeat(const std::vector<T>& values) {
    for (std::size_t i = 0; i < values.size(); ++i) {
        for (std::size_t k = 0; k < i; ++k) {
            if (values[k] == values[i]) return std::make_pair(k, i);
        }
    }
    return std::nullopt;
}

// Each output column once: `-c q1,q1` or `--orders 1,1` wrote a header that jacobid's own CSV reader refuses.
void require_distinct_outputs(const DifferentiateOptions& o) {
    if (const auto r = first_repeat(o.columns)) {
        throw InputError(fmt::format("--columns: '{}' is given twice (entries {} and {}), which would write its columns twice; give each column once",
                                     io::printable_cell(o.columns[r->second]), r->first + 1, r->second + 1));
    }
    if (const auto r = first_repeat(o.orders)) {
        const int n = o.orders[r->second];
        throw InputError(fmt::format("--orders: order {} is given twice (entries {} and {}), which would write the column '{}' twice; give each order once",
                                     n, r->first + 1, r->second + 1, io::printable_cell(channel_name(o.columns.front(), n))));
    }
}

void run(const DifferentiateOptions& o) {
    require_distinct_outputs(o);
    check_outputs({{"--out", o.output}}, {{"--in", o.input}, {"--log-format", o.log_format.file}});
    io::LogColumnNames names;  // q1.., qd1.., tau1.. from the log format's joints
    names.time = o.time_column;
    const LogSegments log = read_log_segments(o.input, o.log_format, names, false);
    for (int n : o.orders) {
        if (n < 0 || n > kMaxOrder) throw InputError(fmt::format("--orders: derivative order {} is not 0, 1, 2 or 3", n));
        if (o.method == "butterworth" && n > 2) throw InputError("--orders: the Butterworth + Euler baseline provides orders 0, 1 and 2");
    }
    if (o.method == "jacobi" && (o.kernel.window > 0.0) == (o.cutoff > 0.0)) {
        throw InputError("--window / --cutoff: give exactly one of them for the Jacobi method");
    }
    if (o.method == "butterworth" && o.butterworth.empty()) throw InputError("--butterworth ORDER:CUTOFF_HZ is required with --method butterworth");
    // One kernel per order for every segment: they share the grid period (docs/log-format.md).
    std::vector<KernelParams> jacobi;
    if (o.method == "jacobi") {
        // With split, every segment is on the reader's grid (a first segment of one row has no step to measure).
        const double ts = log.split && log.grid_period > 0.0 ? log.grid_period
                                                             : io::check_uniform_time(log.tables.front(), o.time_column, o.time_tolerance).sample_period;
        for (int n : o.orders) jacobi.push_back(jacobi_params_for(o, n, ts));
    }
    std::string out = o.time_column;
    for (const std::string& column : o.columns) {
        for (int n : o.orders) out += "," + channel_name(column, n);
    }
    out += log.split ? ",segment\n" : "\n";
    std::size_t rows_in = 0, rows_out = 0, used = 0;
    for (std::size_t s = 0; s < log.tables.size(); ++s) {
        rows_in += log.tables[s].rows();
        std::size_t rows = 0;
        if (!log.split) {
            out += estimate_rows(log.tables[s], o.input, o, jacobi, "", rows);
        } else {
            // Each segment on its own (no window straddles a gap), its rows marked with its 1-based number; a
            // segment too short for the windows is named on stderr, and only when none is long enough is it an error.
            const std::string what = fmt::format("{} segment {} ({})", o.input, s + 1, log.segments[s].describe());
            try {
                out += estimate_rows(log.tables[s], what, o, jacobi, std::to_string(s + 1), rows);
                ++used;
            } catch (const InputError& e) {
                fmt::print(stderr, "{}: segment not written: {}\n", what, e.what());
            }
        }
        rows_out += rows;
    }
    if (log.split && used == 0) throw InputError(fmt::format("{}: --on-gap split: none of the {} segments is long enough for these windows", o.input, log.tables.size()));
    write_output(o.output, out);
    fmt::print(stderr, "{}: {} rows in, {} rows out ({} dropped at the ends, where a window is incomplete){}\n", o.input, rows_in, rows_out,
               rows_in - rows_out, log.split ? fmt::format("; {} of {} segments written", used, log.tables.size()) : std::string());
}

}  // namespace

void add_differentiate_command(CLI::App& app) {
    auto o = std::make_shared<DifferentiateOptions>();
    CLI::App* cmd = app.add_subcommand("differentiate", "estimate derivatives of columns of a CSV log (header row, first column time in seconds)");
    cmd->add_option("--in,-i", o->input, "input CSV log")->required()->check(file_path());
    cmd->add_option("--columns,-c", o->columns, "columns to differentiate, e.g. q1,q2")->required()->delimiter(',');
    cmd->add_option("--time-column", o->time_column, "name of the time column (seconds)")->capture_default_str();
    cmd->add_option("--method", o->method, "jacobi or butterworth (forward-backward Butterworth + central Euler differences)")
        ->check(CLI::IsMember({"jacobi", "butterworth"}))
        ->capture_default_str();
    cmd->add_option("--orders", o->orders, "derivative orders to write (0 = smoothed signal), e.g. 1,2")
        ->delimiter(',')
        ->check(whole_number_in(0, kMaxOrder))
        ->capture_default_str();
    add_kernel_options(cmd, o->kernel, false, false);
    cmd->add_option("--cutoff", o->cutoff, "Jacobi: choose each window so that the cutoff is this frequency in Hz (instead of --window)")
        ->check(positive_number());
    cmd->add_option("--butterworth", o->butterworth, "Butterworth method: ORDER:CUTOFF_HZ, e.g. 4:5");
    cmd->add_option("--crop-edges", o->crop, "Butterworth method: seconds dropped at each end (default 3/cutoff, the filter's end transient)")
        ->check(non_negative_number());
    add_time_tolerance_option(cmd, o->time_tolerance);
    add_log_format_options(cmd, o->log_format);
    cmd->add_option("--out,-o", o->output,
                    "output CSV ('-' = stdout): time, then <column>_d<order> for each column and order (and segment, 1-based, with --on-gap split)")->capture_default_str()->check(file_path(true));
    cmd->callback([o] { run(*o); });
}

}  // namespace jacobid::cli
