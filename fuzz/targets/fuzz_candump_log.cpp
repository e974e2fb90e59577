// SPDX-License-Identifier: MIT
// candump -L logs (host-tools/src/io/candump_log.*) and their conversion to joint samples through the
// device profiles (candump_joints.*), the input of `jacobid identify --can-config`. Bad input must be an
// InputError. Properties: every parsed frame is one a transport could carry (hal::is_valid_frame) or an
// error frame; data frames print (format_candump_line) and parse back to the same frame (time stamp to
// the microseconds the writer keeps); the joint table holds only finite values, one row per sample.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "fuzz_check.hpp"
#include "io/candump_joints.hpp"
#include "io/candump_log.hpp"

using namespace jacobid;

namespace {

// Two MIT motors replying on id 0, a CiA 402 drive (TPDO1 of node 3) and an ODrive (node 4): every
// profile a capture can hold, as fw.yaml would configure them.
std::vector<hal::ProfileConfig> joints() {
    hal::mit::JointConfig m1, m2;
    m1.motor_id = 1;
    m2.motor_id = 2;
    hal::cia402::JointConfig c;
    c.node_id = 3;
    c.counts_per_revolution = 65536.0;
    c.layout.effort = hal::cia402::EffortObject::TorqueActual;
    c.rated_torque = 2.0;
    hal::odrive::JointConfig o;
    o.node_id = 4;
    o.mapping.torque_constant = 0.083;
    return {m1, m2, c, o};
}

bool same_frame(const hal::CanFrame& a, const hal::CanFrame& b) {
    if (a.id != b.id || a.len != b.len || a.flags != b.flags) return false;
    for (std::size_t i = 0; i < a.len && i < a.data.size(); ++i) {
        if (a.data[i] != b.data[i]) return false;
    }
    return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::vector<io::CandumpRecord> records;
    try {
        records = io::parse_candump_log(text, "fuzz.log");
    } catch (const InputError&) {
        return 0;
    }
    for (const io::CandumpRecord& r : records) {
        const hal::CanFrame& f = r.frame;
        if (f.error()) {
            JACOBID_FUZZ_CHECK(f.len <= hal::kCanMaxDataLength && (f.id & ~hal::kCanExtendedIdMask) == 0, "invalid error frame");
            continue;
        }
        JACOBID_FUZZ_CHECK(hal::is_valid_frame(f), "parsed a frame no transport could carry");
        JACOBID_FUZZ_CHECK(!r.interface.empty(), "parsed a frame without an interface");
        if (f.remote()) continue;  // the writer does not keep a remote frame's requested length
        const std::string line = io::format_candump_line(f, r.interface);
        io::CandumpRecord again;
        try {
            again = io::parse_candump_line(line, "again.log", 1);
        } catch (const InputError&) {
            JACOBID_FUZZ_CHECK(false, "a printed frame does not parse");
        }
        JACOBID_FUZZ_CHECK(same_frame(again.frame, f), "print + parse changes the frame");
        JACOBID_FUZZ_CHECK(again.frame.timestamp_ns == f.timestamp_ns / 1000 * 1000, "print + parse changes the time stamp");
    }
    const std::vector<hal::ProfileConfig> config = joints();
    try {
        io::CandumpJointCounts counts;
        const io::CsvTable table = io::candump_joint_table(records, config, {"q1", "q2", "q3", "q4"}, {"tau1", "tau2", "tau3", "tau4"}, "t",
                                                           "fuzz.log", &counts);
        JACOBID_FUZZ_CHECK(table.rows() == counts.samples, "joint table rows differ from the sample count");
        for (std::size_t c = 0; c < table.columns(); ++c) {
            for (double v : table.column(c)) JACOBID_FUZZ_CHECK(std::isfinite(v), "joint table holds a non-finite value");
        }
    } catch (const InputError&) {
    }
    return 0;
}
