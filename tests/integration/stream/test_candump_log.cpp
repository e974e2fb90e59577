// SPDX-License-Identifier: MIT
// candump -L log parser (host-tools/src/io/candump_log.*): hand-checked frames, one-line errors, and
// agreement with python-can's CanutilsLogReader (python_can_reader.py, Debian python3-can) frame by frame.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/candump_log.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace {

using jacobid::io::CandumpRecord;
namespace hal = jacobid::hal;

const char* kHandWritten =
    "(1700000000.123456) can0 123#DEADBEEF\n"
    "(1700000000.123457) can0 1ABCDEF0#0011223344556677\n"
    "(1700000000.200000) vcan1 7FF#\n"
    "\n"
    "(1700000001.000001) can0 321#R\r\n"
    "(1700000001.000002) can0 00000321#R4\n"
    "(1700000002.500000) can0 0C0##1000102030405060708090A0B\n"
    "(1700000002.500001) can0 12345678##3" "000102030405060708090A0B0C0D0E0F101112131415161718191A1B1C1D1E1F\n"
    "(1700000002.600000) can0 456##0\n"
    "(0000000003.000000) can0 000#00 R\n"
    "(1700000004.999999) can0 1FFFFFFF#FF T\n"
    "(1700000005.000000) can0 20000080#0000000000000000\n";

std::string write_file(const std::string& name, const std::string& text) {
    const std::string p = (jacobid::test::scratch_directory() / name).string();
    std::ofstream(p, std::ios::binary) << text;
    return p;
}

TEST(CandumpLog, ParsesEveryFrameKind) {
    const auto r = jacobid::io::parse_candump_log(kHandWritten, "hand.log");
    ASSERT_EQ(r.size(), 11u);

    EXPECT_EQ(r[0].frame.timestamp_ns, 1700000000123456000);
    EXPECT_EQ(r[0].interface, "can0");
    EXPECT_EQ(r[0].frame.id, 0x123u);
    EXPECT_EQ(r[0].frame.flags, 0);
    ASSERT_EQ(r[0].frame.len, 4);
    EXPECT_EQ(r[0].frame.data[0], 0xDE);
    EXPECT_EQ(r[0].frame.data[3], 0xEF);
    EXPECT_EQ(r[0].line, 1u);
    EXPECT_EQ(r[0].direction, 0);

    EXPECT_EQ(r[1].frame.id, 0x1ABCDEF0u);
    EXPECT_TRUE(r[1].frame.extended());
    EXPECT_EQ(r[1].frame.len, 8);
    EXPECT_EQ(r[1].frame.data[7], 0x77);

    EXPECT_EQ(r[2].interface, "vcan1");
    EXPECT_EQ(r[2].frame.id, 0x7FFu);
    EXPECT_EQ(r[2].frame.len, 0);

    EXPECT_EQ(r[3].line, 5u);  // the blank line 4 is skipped but counted
    EXPECT_TRUE(r[3].frame.remote());
    EXPECT_EQ(r[3].frame.len, 0);
    EXPECT_TRUE(r[4].frame.remote());
    EXPECT_TRUE(r[4].frame.extended());
    EXPECT_EQ(r[4].frame.id, 0x321u);
    EXPECT_EQ(r[4].frame.len, 4);

    EXPECT_TRUE(r[5].frame.fd());
    EXPECT_EQ(r[5].frame.flags, hal::kCanFd | hal::kCanBitRateSwitch);
    EXPECT_EQ(r[5].frame.len, 12);
    EXPECT_EQ(r[5].frame.data[11], 0x0B);
    EXPECT_EQ(r[6].frame.flags, hal::kCanFd | hal::kCanBitRateSwitch | hal::kCanErrorStateIndicator | hal::kCanExtended);
    EXPECT_EQ(r[6].frame.len, 32);
    EXPECT_EQ(r[6].frame.data[31], 0x1F);
    EXPECT_EQ(r[7].frame.flags, hal::kCanFd);
    EXPECT_EQ(r[7].frame.len, 0);

    EXPECT_EQ(r[8].frame.timestamp_ns, 3000000000);
    EXPECT_EQ(r[8].direction, 'R');
    EXPECT_EQ(r[9].direction, 'T');
    EXPECT_EQ(r[9].frame.id, 0x1FFFFFFFu);

    EXPECT_TRUE(r[10].frame.error());
    EXPECT_FALSE(r[10].frame.extended());
    EXPECT_EQ(r[10].frame.id, 0x80u);  // CAN_ERR_BUSERROR
    EXPECT_EQ(r[10].frame.len, 8);
    for (const CandumpRecord& rec : r) {
        if (!rec.frame.error()) {
            EXPECT_TRUE(hal::is_valid_frame(rec.frame)) << "line " << rec.line;
        }
    }
}

TEST(CandumpLog, KeepsNanosecondsAndShortFractionsExactly) {
    const auto r = jacobid::io::parse_candump_log("(1.5) can0 001#\n(9223372035.999999999) can0 001#\n", "t.log");
    ASSERT_EQ(r.size(), 2u);
    EXPECT_EQ(r[0].frame.timestamp_ns, 1500000000);
    EXPECT_EQ(r[1].frame.timestamp_ns, 9223372035999999999);
}

// Each bad line must fail with "file:line: <what was expected>", on one line.
TEST(CandumpLog, RejectsMalformedLinesNamingFileLineAndExpectation) {
    struct Case {
        const char* line;
        const char* expected;  // a fragment of the message
    };
    const Case cases[] = {
        {"1700000000.1 can0 123#00", "expected a time stamp '(seconds.fraction)'"},
        {"(1700000000) can0 123#00", "expected a time stamp"},
        {"(17000x0000.1) can0 123#00", "expected a time stamp"},
        {"(1.1234567891) can0 123#00", "more than 9 decimals"},
        {"(99999999999.0) can0 123#00", "too large"},
        {"(1.0) can0", "found 2 field(s)"},
        {"(1.0) can0 123#00 R extra", "found 5 field(s)"},
        {"(1.0) can0 12300", "expected a frame '<id>#<data>'"},
        {"(1.0) can0 1234#00", "3 hex digits (standard) or 8 (extended)"},
        {"(1.0) can0 12G#00", "'G' is not a hex digit"},
        {"(1.0) can0 800#00", "exceeds 7FF"},
        {"(1.0) can0 40000000#00", "extended identifier 40000000 exceeds 1FFFFFFF"},
        {"(1.0) can0 60000000#00", "bits beyond 29 bits and CAN_ERR_FLAG"},
        {"(1.0) can0 123#ABC", "odd number of hex digits"},
        {"(1.0) can0 123#001122334455667788", "9 bytes, more than the 8 a classic CAN frame carries"},
        {"(1.0) can0 123#00.11", "'.' separators are cansend syntax"},
        {"(1.0) can0 123#0011223344556677_9", "raw DLC suffix"},
        {"(1.0) can0 123#ZZ", "'Z' is not a hex digit"},
        {"(1.0) can0 123#R9", "expected 'R' or 'R' and a length digit 0-8"},
        {"(1.0) can0 123#R12", "expected 'R' or 'R' and a length digit"},
        {"(1.0) can0 123##", "expected a flags digit after '##'"},
        {"(1.0) can0 123##8", "flags digit '8' is not 0-7"},
        {"(1.0) can0 123##1000102030405060708", "9 data bytes; FD lengths are"},
        {"(1.0) can0 20000004##100", "error frame cannot be a CAN FD frame"},
        {"(1.0) can0 123#00 X", "expected direction 'R' or 'T'"},
    };
    for (const Case& c : cases) {
        const std::string text = std::string("(0.5) can0 100#01\n\n") + c.line + "\n";
        try {
            jacobid::io::parse_candump_log(text, "bad.log");
            ADD_FAILURE() << "accepted: " << c.line;
        } catch (const jacobid::InputError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind("bad.log:3: ", 0), 0u) << what;
            EXPECT_NE(what.find(c.expected), std::string::npos) << "line: " << c.line << "\nmessage: " << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
}

TEST(CandumpLog, MissingFileIsAnInputError) {
    EXPECT_THROW(jacobid::io::read_candump_log("/nonexistent/dir/x.log"), jacobid::InputError);
}

struct PythonFrame {
    std::string timestamp_text;
    long long timestamp_us = 0;
    int extended = 0, remote = 0, fd = 0, error = 0, brs = 0, esi = 0;
    unsigned long id = 0;
    int dlc = 0;
    std::string data;
};

std::vector<PythonFrame> read_with_python_can(const std::string& path) {
    const std::string script = std::string(JACOBID_TESTS_DIR) + "/integration/stream/python_can_reader.py";
    const auto result = jacobid::test::run_command(std::string("\"") + JACOBID_REFERENCE_PYTHON + "\" \"" + script + "\" \"" + path + "\"");
    EXPECT_EQ(result.exit_code, 0) << "python-can reader failed (is Debian's python3-can installed?)\n" << result.err;
    std::vector<PythonFrame> frames;
    std::istringstream lines(result.out);
    for (std::string line; std::getline(lines, line);) {
        std::istringstream f(line);
        PythonFrame p;
        f >> p.timestamp_text >> p.timestamp_us >> p.extended >> p.remote >> p.fd >> p.error >> p.brs >> p.esi >> std::hex >> p.id >>
            std::dec >> p.dlc >> p.data;
        EXPECT_FALSE(f.fail()) << line;
        frames.push_back(p);
    }
    return frames;
}

std::string hex_data(const hal::CanFrame& f) {
    if (f.remote() || f.len == 0) return "-";
    std::string s;
    char b[3];
    for (std::size_t i = 0; i < f.len; ++i) {
        std::snprintf(b, sizeof b, "%02X", f.data[i]);
        s += b;
    }
    return s;
}

void expect_same_as_python_can(const std::string& path) {
    const std::vector<CandumpRecord> ours = jacobid::io::read_candump_log(path);
    const std::vector<PythonFrame> theirs = read_with_python_can(path);
    ASSERT_EQ(ours.size(), theirs.size());
    for (std::size_t i = 0; i < ours.size(); ++i) {
        const hal::CanFrame& f = ours[i].frame;
        const PythonFrame& p = theirs[i];
        SCOPED_TRACE(path + " line " + std::to_string(ours[i].line));
        EXPECT_EQ(f.timestamp_ns, p.timestamp_us * 1000);
        // The double python holds is the correctly rounded decimal; ours converted to double agrees to
        // within the rounding of a double at this magnitude (about 0.24 us near 1.7e9 s).
        EXPECT_NEAR(static_cast<double>(f.timestamp_ns) * 1e-9, std::strtod(p.timestamp_text.c_str(), nullptr), 5e-7);
        EXPECT_EQ(f.error(), p.error != 0);
        if (f.error()) continue;  // python-can keeps neither id nor data of error frames
        EXPECT_EQ(f.id, p.id);
        EXPECT_EQ(f.extended(), p.extended != 0);
        EXPECT_EQ(f.remote(), p.remote != 0);
        EXPECT_EQ(f.fd(), p.fd != 0);
        EXPECT_EQ((f.flags & hal::kCanBitRateSwitch) != 0, p.brs != 0);
        EXPECT_EQ((f.flags & hal::kCanErrorStateIndicator) != 0, p.esi != 0);
        EXPECT_EQ(f.len, p.dlc);
        EXPECT_EQ(hex_data(f), p.data);
    }
}

TEST(CandumpLog, AgreesWithPythonCanOnTheHandWrittenLog) { expect_same_as_python_can(write_file("hand.log", kHandWritten)); }

// A longer log in candump's own layout ("(%010lu.%06lu) %s %s"), formatted here without the parser.
TEST(CandumpLog, AgreesWithPythonCanOnARandomLog) {
    std::mt19937 rng_engine(7);
    auto rng = [&rng_engine] { return static_cast<unsigned>(rng_engine()); };
    std::string text;
    long long us = 1700000000000000LL;
    const int fd_lengths[] = {0, 1, 5, 8, 12, 16, 20, 24, 32, 48, 64};
    char buffer[256];
    for (int i = 0; i < 600; ++i) {
        us += 1 + rng() % 5000;
        std::snprintf(buffer, sizeof buffer, "(%010lld.%06lld) can%u ", us / 1000000, us % 1000000, rng() % 2);
        text += buffer;
        const unsigned kind = rng() % 6;
        const bool extended = rng() % 3 == 0;
        const unsigned id = extended ? rng() & 0x1FFFFFFFu : rng() & 0x7FFu;
        std::snprintf(buffer, sizeof buffer, extended ? "%08X" : "%03X", id);
        text += buffer;
        int len = 0;
        if (kind == 0) {  // remote
            len = static_cast<int>(rng() % 9);
            text += len ? "#R" + std::to_string(len) : std::string("#R");
            len = 0;
        } else if (kind == 1) {  // FD
            len = fd_lengths[rng() % 11];
            text += "##" + std::to_string(rng() % 4);
        } else {
            len = static_cast<int>(rng() % 9);
            text += "#";
        }
        for (int b = 0; b < len; ++b) {
            std::snprintf(buffer, sizeof buffer, "%02X", rng() % 256);
            text += buffer;
        }
        text += "\n";
    }
    expect_same_as_python_can(write_file("random.log", text));
}

}  // namespace
