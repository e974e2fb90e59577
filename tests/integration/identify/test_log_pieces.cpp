// SPDX-License-Identifier: MIT
// identify on a CSV log longer than one piece (issue 18, job/streamed_log.hpp): the log is read and identified
// piece by piece, consecutive pieces sharing one row. Checked against the same rows written by the test as
// separate files and given as several logs (identify --in a --in b --in c, test_several_logs.cpp checks
// that path against stacked least squares), against the whole log (only the seams and the first piece's
// plan may differ), and for the refusals: a time gap where two pieces meet, --piece-rows where pieces
// cannot serve.
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_command.hpp"
#include "simulated_log.hpp"
#include "scratch_directory.hpp"

namespace {

using nlohmann::json;

std::string path(const std::string& name) { return (jacobid::test::scratch_directory() / name).string(); }
jacobid::test::CommandResult jacobid_cli(const std::string& args) { return jacobid::test::run_command(std::string(JACOBID_EXECUTABLE) + " " + args); }

constexpr std::size_t kPiece = 20000;
constexpr std::size_t kRows = kPiece + 2 * (kPiece - 1);  // three pieces of exactly kPiece rows

// A simulated planar 2R log of kRows rows (1 kHz), its lines, and the robot.
struct Log {
    std::string robot = path("robot.yaml"), csv = path("long.csv");
    std::string header;
    std::vector<std::string> rows;
    Log() {
        std::ofstream(robot) << "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100}\n";
        const std::string simulated = path("simulated.csv");
        const auto r = jacobid::test::simulated_log(simulated, "--quiet --robot " + robot +
                                           " --duration 60 --seed 3 --noise-seed 13 --encoder-counts 65536 --torque-noise 0.05,0.01");
        EXPECT_EQ(r.exit_code, 0) << r.err;
        std::ifstream in(simulated);
        std::getline(in, header);
        for (std::string line; rows.size() < kRows && std::getline(in, line);) rows.push_back(line);
        EXPECT_EQ(rows.size(), kRows);
        write(csv, 0, kRows);
    }
    // Rows [begin, end) under the header.
    void write(const std::string& file, std::size_t begin, std::size_t end) const {
        std::ofstream out(file);
        out << header << '\n';
        for (std::size_t i = begin; i < end; ++i) out << rows[i] << '\n';
    }
    // All rows under the header, the time of each row i >= kPiece (the second piece's first new row on) set to
    // new_time(i, its time).
    void write_with_later_times(const std::string& file, const std::function<double(std::size_t, double)>& new_time) const {
        std::ofstream out(file);
        out << header << '\n';
        for (std::size_t i = 0; i < kRows; ++i) {
            std::string row = rows[i];
            if (i >= kPiece) {
                const std::size_t comma = row.find(',');
                row = fmt::format("{:.6f}", new_time(i, std::stod(row.substr(0, comma)))) + row.substr(comma);
            }
            out << row << '\n';
        }
    }
    std::string identify(const std::string& extra, const std::string& torque_delay = "0") const {
        return "identify --quiet --robot " + robot + " --torque-delay " + torque_delay + " " + extra;
    }
};

const Log& log() {
    static const Log l;
    return l;
}

json run_json(const std::string& args) {
    const auto r = jacobid_cli(args + " --format json");
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    return json::parse(r.out.empty() ? "{}" : r.out);
}

const json& parameters(const json& j) { return j["methods"]["jacobi"]["parameters"]; }

TEST(LogPieces, EqualTheSameRowsGivenAsSeparateLogs) {
    const Log& l = log();
    std::string ins;
    for (std::size_t k = 0; k < 3; ++k) {
        const std::string file = path(fmt::format("piece{}.csv", k + 1));
        l.write(file, k * (kPiece - 1), k * (kPiece - 1) + kPiece);  // each starts with the previous one's last row
        ins += " --in " + file;
    }
    const json pieces = run_json(l.identify("--in " + l.csv + " --piece-rows " + std::to_string(kPiece)));
    const json logs = run_json(l.identify(ins));
    ASSERT_FALSE(parameters(pieces).empty());
    for (const auto& [name, p] : parameters(logs).items()) {
        const double v = p["value"].get<double>(), s = p["std"].get<double>();
        EXPECT_NEAR(parameters(pieces)[name]["value"].get<double>(), v, 1e-10 * std::abs(v)) << name;
        EXPECT_NEAR(parameters(pieces)[name]["std"].get<double>(), s, 1e-8 * s) << name;
    }
    // With the torques read 0.4 samples later: the first piece's are aligned in place before the smoothing
    // choice, the later pieces' by the pipeline, each once, as each separate log's is.
    const json pieces_delayed = run_json(l.identify("--in " + l.csv + " --piece-rows " + std::to_string(kPiece), "0.0004"));
    const json logs_delayed = run_json(l.identify(ins, "0.0004"));
    for (const auto& [name, p] : parameters(logs_delayed).items()) {
        const double v = p["value"].get<double>();
        EXPECT_NEAR(parameters(pieces_delayed)[name]["value"].get<double>(), v, 1e-10 * std::abs(v)) << name;
        EXPECT_NE(p["value"], parameters(logs)[name]["value"]) << name << ": the delay is applied";
    }
    // The first piece is freed once identified and read again for the next method: the second method's
    // result (and the first's) is what it gives alone.
    const json both = run_json(l.identify("--in " + l.csv + " --piece-rows " + std::to_string(kPiece) + " --method both"));
    const json butterworth = run_json(l.identify("--in " + l.csv + " --piece-rows " + std::to_string(kPiece) + " --method butterworth"));
    for (const auto& [name, p] : parameters(pieces).items()) {
        EXPECT_EQ(both["methods"]["jacobi"]["parameters"][name]["value"], p["value"]) << name;
        EXPECT_EQ(both["methods"]["butterworth"]["parameters"][name]["value"], butterworth["methods"]["butterworth"]["parameters"][name]["value"]) << name;
    }
    EXPECT_EQ(both["methods"]["butterworth"]["segments"].size(), 3u);
    // Each piece reported with its lines in the file (the header is line 1) and its equations.
    const json& segments = pieces["methods"]["jacobi"]["segments"];
    ASSERT_EQ(segments.size(), 3u) << pieces.dump(1);
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(segments[k]["first_line"], 2 + k * (kPiece - 1));
        EXPECT_EQ(segments[k]["last_line"], 1 + kPiece + k * (kPiece - 1));
        EXPECT_EQ(segments[k]["samples"], kPiece);
        EXPECT_EQ(segments[k]["log"], l.csv);
        EXPECT_EQ(segments[k]["rows"], logs["methods"]["jacobi"]["segments"][k]["rows"]);
        EXPECT_TRUE(segments[k]["used"].get<bool>());
    }
}

// The pieces lose the equations within a window of each seam and take their plan from the first piece (here
// a bandwidth of 2.01 Hz where the whole log's is 1.86 Hz: other windows and decimation, measured), so they
// are not the whole log's equations: the parameters stay within half their standard deviation of the whole
// log's (measured: at most 0.31, FC1), and the std within 15 % (measured: at most 8 %; one piece of the three
// alone would give sqrt(3) = 1.73 x).
TEST(LogPieces, StayCloseToTheWholeLog) {
    const Log& l = log();
    const json pieces = run_json(l.identify("--in " + l.csv + " --piece-rows " + std::to_string(kPiece)));
    const json whole = run_json(l.identify("--in " + l.csv));
    EXPECT_FALSE(whole["methods"]["jacobi"].contains("segments") && !whole["methods"]["jacobi"]["segments"].empty()) << "one piece: the whole log";
    for (const auto& [name, p] : parameters(whole).items()) {
        const double v = p["value"].get<double>(), s = p["std"].get<double>();
        EXPECT_NEAR(parameters(pieces)[name]["value"].get<double>(), v, 0.5 * s) << name;
        EXPECT_NEAR(parameters(pieces)[name]["std"].get<double>(), s, 0.15 * s) << name;
    }
}

TEST(LogPieces, ATimeGapWherePiecesMeetIsFound) {
    const Log& l = log();
    // 0.1 s added to every time after the first piece's last row: the step out of it is a gap.
    const std::string file = path("gap.csv");
    l.write_with_later_times(file, [](std::size_t, double t) { return t + 0.1; });
    const auto r = jacobid_cli(l.identify("--in " + file + " --piece-rows " + std::to_string(kPiece)));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(fmt::format("{}:{}:", file, kPiece + 2)), std::string::npos) << r.err;
}

TEST(LogPieces, ASamplePeriodThatChangesFromOnePieceToTheNextIsRefused) {
    const Log& l = log();
    // From the first piece's last row on, every step is 2 ms: the second piece is uniform, on another period.
    const std::string file = path("slower.csv");
    l.write_with_later_times(file, [](std::size_t i, double) {
        return 1e-3 * static_cast<double>(kPiece - 1) + 2e-3 * static_cast<double>(i - (kPiece - 1));
    });
    const auto r = jacobid_cli(l.identify("--in " + file + " --piece-rows " + std::to_string(kPiece)));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(fmt::format("{}: piece 2 (lines {}-{}): sampled every 2 ms, but the first piece every 1 ms", file, kPiece + 1, 2 * kPiece)),
              std::string::npos)
        << r.err;
}

TEST(LogPieces, PieceRowsAreRefusedWherePiecesCannotServe) {
    const Log& l = log();
    l.write(path("other.csv"), 0, 5000);
    for (const std::string& extra : std::vector<std::string>{"--estimator didim", "--period auto", "--in " + path("other.csv")}) {
        const auto r = jacobid_cli(l.identify("--in " + l.csv + " --piece-rows 20000 " + extra));
        EXPECT_EQ(r.exit_code, 2) << extra;
        EXPECT_NE(r.err.find("--piece-rows"), std::string::npos) << extra << ": " << r.err;
    }
}

}  // namespace
