// SPDX-License-Identifier: MIT
// Numeric CSV logs (host-tools/src/io/csv_table.*, time_axis.*), the input of `jacobid identify` and
// `jacobid differentiate`. Bad input must be an InputError (exit 2), never another exception or a crash.
// Properties of an accepted table: rectangular, every value finite, and printing it with 17 significant
// digits and parsing it again gives the same doubles bit for bit (a mis-read number would not survive);
// an accepted time axis has a finite positive period and one sample per row.
#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "core/errors.hpp"
#include "fuzz_check.hpp"
#include "io/csv_table.hpp"
#include "io/time_axis.hpp"

using namespace jacobid;

namespace {

std::string print_table(const io::CsvTable& t) {
    std::string text;
    for (std::size_t c = 0; c < t.columns(); ++c) text += (c ? "," : "") + t.header()[c];
    text += '\n';
    for (std::size_t r = 0; r < t.rows(); ++r) {
        for (std::size_t c = 0; c < t.columns(); ++c) text += fmt::format("{}{:.17g}", c ? "," : "", t.column(c)[r]);
        text += '\n';
    }
    return text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    io::CsvTable table;
    try {
        table = io::parse_csv(text, "fuzz.csv");
    } catch (const InputError&) {
        return 0;
    }
    JACOBID_FUZZ_CHECK(table.columns() >= 1, "accepted a table without columns");
    for (std::size_t c = 0; c < table.columns(); ++c) {
        JACOBID_FUZZ_CHECK(table.column(c).size() == table.rows(), "columns of different lengths");
        for (double v : table.column(c)) JACOBID_FUZZ_CHECK(std::isfinite(v) && !io::beyond_log_range(v), "accepted a non-finite value or one beyond +-1e30");
    }
    io::CsvTable again;
    try {
        again = io::parse_csv(print_table(table), "again.csv");
    } catch (const InputError&) {
        JACOBID_FUZZ_CHECK(false, "the printed copy of an accepted table is rejected");
    }
    JACOBID_FUZZ_CHECK(again.header() == table.header() && again.rows() == table.rows(), "printed copy has another shape");
    // A header without rows leaves the columns unallocated (data() null): memcmp of null, even for 0 bytes,
    // is undefined (found by this target once the reader stopped reserving before the first row).
    for (std::size_t c = 0; c < table.columns() && table.rows() > 0; ++c) {
        JACOBID_FUZZ_CHECK(std::memcmp(again.column(c).data(), table.column(c).data(), table.rows() * sizeof(double)) == 0,
                           "a value does not survive printing with 17 digits and parsing again");
    }
    try {
        const io::TimeAxis axis = io::check_uniform_time(table, table.header().front());
        JACOBID_FUZZ_CHECK(std::isfinite(axis.sample_period) && axis.sample_period > 0.0, "accepted time axis without a positive period");
        JACOBID_FUZZ_CHECK(axis.samples == table.rows(), "time axis sample count differs from the rows");
    } catch (const InputError&) {
    }
    return 0;
}
