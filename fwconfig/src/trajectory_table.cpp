// SPDX-License-Identifier: MIT
#include "jacobid/fwconfig/trajectory_table.hpp"

#include <fmt/core.h>

#include <charconv>
#include <cmath>
#include <sstream>
#include <map>
#include <optional>

#include "jacobid/fwconfig/firmware_config_yaml.hpp"
#include "jacobid/yaml/input_file.hpp"

namespace jacobid::firmware {
namespace {

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> cells;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= line.size(); ++i) {
        if (i == line.size() || line[i] == ',') {
            cells.push_back(line.substr(start, i - start));
            start = i + 1;
        }
    }
    if (!cells.empty() && !cells.back().empty() && cells.back().back() == '\r') cells.back().pop_back();
    return cells;
}

// The joint a per-joint column names ("qd3" -> 3; q, qd, qdd, tau), or 0 for any other column.
std::size_t joint_of_column(const std::string& name) {
    for (const char* prefix : {"qdd", "qd", "q", "tau"}) {
        const std::string p = prefix;
        if (name.size() <= p.size() || name.compare(0, p.size(), p) != 0) continue;
        std::size_t joint = 0;
        const auto [end, ec] = std::from_chars(name.data() + p.size(), name.data() + name.size(), joint);
        return ec == std::errc() && end == name.data() + name.size() ? joint : 0;
    }
    return 0;
}

}  // namespace

std::vector<TrajectoryRow> load_trajectory_table(const std::string& path, std::size_t joints, double rate, bool torques) {
    // The one reader of input files (a regular file of bounded size: /dev/zero would be read forever).
    std::istringstream in(yaml::read_input_file<ConfigError>(path, "the trajectory table"));
    std::string line;
    if (!std::getline(in, line)) throw ConfigError(fmt::format("{}: empty trajectory table (expected a header t,q1,..,qd1,..)", path));
    const std::vector<std::string> header = split(line);
    std::map<std::string, std::size_t> column;
    for (std::size_t c = 0; c < header.size(); ++c) {
        if (!column.emplace(header[c], c).second) throw ConfigError(fmt::format("{}:1:{}: column '{}' appears twice", path, c + 1, header[c]));
        // A table for more joints than fw.yaml has would have those columns dropped silently.
        if (joint_of_column(header[c]) > joints) {
            throw ConfigError(fmt::format("{}:1:{}: column '{}' is for joint {}, but fw.yaml has {} joint{}: a table for another robot? (its values "
                                          "would not be played)",
                                          path, c + 1, header[c], joint_of_column(header[c]), joints, joints == 1 ? "" : "s"));
        }
    }
    auto find = [&](const std::string& name, bool required) -> std::optional<std::size_t> {
        const auto it = column.find(name);
        if (it != column.end()) return it->second;
        if (required) throw ConfigError(fmt::format("{}:1: no column '{}' (expected t, q1..q{}, qd1..qd{}{})", path, name, joints, joints,
                                                    torques ? fmt::format(" and tau1..tau{} for torque mode", joints) : ""));
        return std::nullopt;
    };
    const std::size_t t_column = *find("t", true);
    std::vector<std::size_t> q, qd;
    std::vector<std::optional<std::size_t>> tau;
    for (std::size_t j = 1; j <= joints; ++j) {
        q.push_back(*find(fmt::format("q{}", j), true));
        qd.push_back(*find(fmt::format("qd{}", j), true));
        tau.push_back(find(fmt::format("tau{}", j), torques));
    }
    const double period = 1.0 / rate;
    std::vector<TrajectoryRow> rows;
    for (std::size_t number = 2; std::getline(in, line); ++number) {
        if (line.empty() || line == "\r") continue;
        const std::vector<std::string> cells = split(line);
        if (cells.size() != header.size()) {
            throw ConfigError(fmt::format("{}:{}: {} cells, the header has {}", path, number, cells.size(), header.size()));
        }
        auto value = [&](std::size_t c) {
            const std::string& text = cells[c];
            double v = 0.0;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
            if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v)) {
                throw ConfigError(fmt::format("{}:{}:{}: column {}: '{}' is not a finite number", path, number, c + 1, header[c], text));
            }
            return v;
        };
        const double t = value(t_column);
        const double expected = static_cast<double>(rows.size()) * period;
        if (std::abs(t - expected) > 1e-3 * period + 1e-12 * std::abs(expected)) {
            throw ConfigError(fmt::format("{}:{}:{}: t = {} s, expected {} s: the table must hold one row per control cycle ({} Hz) from t = 0",
                                          path, number, t_column + 1, t, expected, rate));
        }
        TrajectoryRow r;
        r.line = number;
        for (std::size_t j = 0; j < joints; ++j) {
            r.q[j] = value(q[j]);
            r.qd[j] = value(qd[j]);
            r.tau[j] = tau[j] ? value(*tau[j]) : 0.0;
        }
        rows.push_back(r);
    }
    if (rows.size() < 2) throw ConfigError(fmt::format("{}: {} rows, a trajectory needs at least two", path, rows.size()));
    return rows;
}

}  // namespace jacobid::firmware
