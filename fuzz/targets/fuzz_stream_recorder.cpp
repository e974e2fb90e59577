// SPDX-License-Identifier: MIT
// The host's receive path of the estimate stream (host-tools/src/stream/recorder.*, sequence_tracker.*):
// a fuzzed sequence of datagrams, some raw bytes (garbage, truncated, oversized) and some well-formed
// ones with fuzzed sequence numbers, flags, joint counts and values, recorded under a fuzzed gap policy.
// Properties: every datagram is accounted for (malformed, or pushed and then written, duplicated or
// late); the holes/warnings/summary render; under --on-gap split without estimates every file written
// is a log `jacobid identify` accepts (parse_csv) with the row count the recorder reports.
#include <fuzzer/FuzzedDataProvider.h>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "fuzz_check.hpp"
#include "scratch_directory.hpp"
#include "io/csv_table.hpp"
#include "stream/recorder.hpp"

using namespace jacobid;

namespace {

std::vector<std::uint8_t> well_formed(FuzzedDataProvider& in, std::uint64_t& sequence) {
    stream::EstimateDatagram<4> d;
    d.joint_count = in.ConsumeIntegralInRange<std::size_t>(1, 4);
    // Mostly the next number, sometimes a small step back or ahead, sometimes anything.
    const int step = in.ConsumeIntegralInRange<int>(0, 9);
    sequence = step < 6 ? sequence + 1 : step < 9 ? sequence + static_cast<std::uint64_t>(in.ConsumeIntegralInRange<int>(-40, 40))
                                                  : in.ConsumeIntegral<std::uint64_t>();
    d.sequence = sequence;
    d.sample_index = in.ConsumeBool() ? sequence : in.ConsumeIntegral<std::uint64_t>();
    d.flags = in.ConsumeIntegralInRange<std::uint32_t>(0, 3);
    d.delay_samples = in.ConsumeIntegralInRange<std::uint32_t>(0, 100);
    d.timestamp_ns = in.ConsumeIntegral<std::int64_t>();
    d.sample_period = in.ConsumeBool() ? 0.001 : in.ConsumeFloatingPoint<double>();
    for (std::size_t j = 0; j < d.joint_count; ++j) {
        auto& e = d.joints[j];
        e.flags = in.ConsumeIntegralInRange<std::uint32_t>(0, 15);
        e.q = in.ConsumeFloatingPoint<double>();
        e.tau = in.ConsumeFloatingPoint<double>();
        e.q_hat = in.ConsumeFloatingPoint<double>();
        e.qd_hat = in.ConsumeFloatingPoint<double>();
        e.qdd_hat = in.ConsumeFloatingPoint<double>();
    }
    std::vector<std::uint8_t> bytes(stream::datagram_size(d.joint_count, d.version));
    std::size_t written = 0;
    // Values encode() refuses go out as raw bytes anyway: a buggy or foreign sender could send them.
    if (stream::encode(d, Span<std::uint8_t>(bytes.data(), bytes.size()), written) != stream::DatagramStatus::Ok) {
        bytes = in.ConsumeBytes<std::uint8_t>(in.ConsumeIntegralInRange<std::size_t>(0, 300));
    }
    return bytes;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    stream::RecorderOptions options;
    options.output = (fuzz::scratch_directory("recorder") / "log.csv").string();
    options.policy = in.PickValueInArray({stream::GapPolicy::Error, stream::GapPolicy::Split, stream::GapPolicy::Mark});
    options.estimates = in.ConsumeBool();
    options.reorder_window = in.ConsumeIntegralInRange<std::size_t>(1, 8);
    std::uint64_t pushed = 0;
    {
        stream::Recorder recorder(options);
        std::uint64_t sequence = in.ConsumeIntegral<std::uint64_t>();
        while (in.remaining_bytes() > 0) {
            std::vector<std::uint8_t> bytes = in.ConsumeBool() ? well_formed(in, sequence)
                                                               : in.ConsumeBytes<std::uint8_t>(in.ConsumeIntegralInRange<std::size_t>(0, 400));
            const std::size_t full_size = in.ConsumeIntegralInRange<int>(0, 15) == 0 ? bytes.size() + 1 : bytes.size();
            const std::uint64_t malformed_before = recorder.malformed();
            recorder.datagram(bytes, full_size);
            pushed += recorder.malformed() == malformed_before ? 1 : 0;
        }
        recorder.finish();
        const stream::SequenceCounts& c = recorder.tracker().counts();
        JACOBID_FUZZ_CHECK(c.written + c.duplicated + c.late == pushed, "a datagram was neither written, duplicated nor late");
        JACOBID_FUZZ_CHECK(recorder.rows_written() <= c.written, "more rows than datagrams written in order");
        (void)recorder.holes();
        (void)recorder.warnings();
        (void)recorder.summary().dump();
        (void)recorder.progress_line(1.0);
        if (options.policy == stream::GapPolicy::Split && !options.estimates) {
            for (const stream::OutputFile& f : recorder.files()) {
                try {
                    const io::CsvTable t = io::read_csv(f.path);
                    JACOBID_FUZZ_CHECK(t.rows() == f.rows, "a recorded file holds another number of rows than reported");
                } catch (const InputError& e) {
                    std::fprintf(stderr, "read_csv: %s\n", e.what());
                    JACOBID_FUZZ_CHECK(false, "a recorded file (--on-gap split) is not a valid CSV log");
                }
            }
        }
    }
    std::filesystem::remove_all(fuzz::scratch_directory("recorder"));
    std::filesystem::create_directories(fuzz::scratch_directory("recorder"));
    return 0;
}
