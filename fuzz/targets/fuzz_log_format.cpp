// SPDX-License-Identifier: MIT
// A YAML log format and a raw log (host-tools/src/io/log_format.*, `--log-format`), read by identify,
// diagnose and differentiate. The input is the format, a line "---", then the log; the log is read strictly
// and, with --skip-bad-rows, leniently. Any input must either be read or raise InputError (exit 2), never
// another exception or a crash. Properties of an accepted log: one uniform, increasing time grid as long as
// every column, every value finite, as many columns as the format asks for (time, positions, logged
// velocities, torques), and no more rows kept than the log has lines.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/errors.hpp"
#include "fuzz_check.hpp"
#include "io/log_format.hpp"

using namespace jacobid;

namespace {

void check_table(const io::CsvTable& t, const io::LogFormat& f, const io::LogReadReport& r) {
    std::size_t velocities = 0;
    for (const auto& v : f.velocities) velocities += v.present();
    JACOBID_FUZZ_CHECK(t.columns() == 1 + 2 * f.joints() + velocities, "wrong number of columns");
    JACOBID_FUZZ_CHECK(t.rows() == r.samples && r.samples >= 1, "table and report disagree on the grid");
    JACOBID_FUZZ_CHECK(r.rows + r.skipped.size() <= r.lines, "more rows than lines");
    for (std::size_t c = 0; c < t.columns(); ++c) {
        JACOBID_FUZZ_CHECK(t.column(c).size() == t.rows(), "ragged table");
        for (const double v : t.column(c)) JACOBID_FUZZ_CHECK(std::isfinite(v), "non-finite value");
    }
    const auto& time = t.column(std::size_t{0});
    for (std::size_t k = 1; k < time.size(); ++k) JACOBID_FUZZ_CHECK(time[k] >= time[k - 1], "time decreases on the grid");
    JACOBID_FUZZ_CHECK(r.grid_period > 0.0 && std::isfinite(r.grid_period), "grid period not positive");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    const std::size_t split = input.find("\n---\n");
    const std::string yaml = input.substr(0, split);
    const std::string log = split == std::string::npos ? std::string() : input.substr(split + 5);
    io::LogFormat format;
    try {
        format = io::parse_log_format(yaml, "format.yaml");
    } catch (const InputError&) {
        return 0;
    }
    JACOBID_FUZZ_CHECK(format.joints() >= 1 && format.efforts.size() == format.joints() && format.gains.size() == format.joints(),
                       "accepted format with inconsistent lists");
    for (const bool skip : {false, true}) {
        io::LogReadSettings settings;
        settings.skip_bad_rows = skip;
        settings.on_gap = skip ? io::GapPolicy::Interpolate : io::GapPolicy::Error;
        io::LogReadReport report;
        try {
            const io::CsvTable t = io::parse_formatted_log(log, "log.csv", format, io::LogColumnNames::numbered(format.joints()), settings, report);
            check_table(t, format, report);
        } catch (const InputError&) {
        }
    }
    return 0;
}
