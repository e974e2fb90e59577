// SPDX-License-Identifier: MIT
#include "monitor/monitor_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "plot/gnuplot.hpp"

namespace jacobid::monitor {
namespace {

std::string joint_list(const std::vector<int>& joints) {
    std::string s;
    for (const int j : joints) s += fmt::format("{}{}", s.empty() ? "" : ",", j + 1);
    return s;
}

}  // namespace

std::string events_text(const std::vector<ContactEvent>& events, const Replay& replay, const robot::RobotDescription& robot) {
    std::string s = fmt::format("{} contact event(s); estimates delayed by the differentiators' {:.1f} ms\n", events.size(), 1e3 * replay.delay);
    if (events.empty()) return s;
    s += fmt::format("{:>3}  {:>10}  {:>10}  {:>8}  {:<8}  peak external torque per joint (N.m)\n", "#", "start (s)", "end (s)", "ms", "joints");
    for (std::size_t k = 0; k < events.size(); ++k) {
        const ContactEvent& e = events[k];
        std::string peaks;
        for (std::size_t j = 0; j < robot.joints.size(); ++j) peaks += fmt::format(" {:+8.2f}", e.peak[j]);
        s += fmt::format("{:>3}  {:>10.3f}  {:>10.3f}  {:>8.0f}  {:<8} {}\n", k + 1, e.start, e.end, 1e3 * (e.end - e.start), joint_list(e.joints), peaks);
    }
    return s;
}

nlohmann::json events_json(const std::vector<ContactEvent>& events, const Replay& replay, const MonitorFile& monitor,
                           const robot::RobotDescription& robot, const std::string& log) {
    nlohmann::json j;
    j["log"] = log;
    j["estimator"] = to_string(monitor.estimator.estimator);
    j["delay"] = replay.delay;
    j["samples"] = replay.t.size();
    j["thresholds"] = nlohmann::json::array();
    for (std::size_t k = 0; k < robot.joints.size(); ++k) {
        j["thresholds"].push_back({{"joint", k + 1}, {"name", robot.joints[k].name}, {"moving", monitor.thresholds[k].moving}, {"standing", monitor.thresholds[k].standing}});
    }
    j["events"] = nlohmann::json::array();
    for (const ContactEvent& e : events) {
        nlohmann::json joints = nlohmann::json::array();
        for (const int k : e.joints) joints.push_back(k + 1);
        j["events"].push_back({{"start", e.start}, {"end", e.end}, {"joints", joints}, {"peak", e.peak}, {"peak_time", e.peak_time}, {"median", e.median}});
    }
    return j;
}

void plot_events(const std::string& png, const std::vector<ContactEvent>& events, const Replay& replay, const MonitorFile& monitor,
                 const robot::RobotDescription& robot, const std::string& title) {
    std::vector<plot::Panel> panels;
    std::string shading;
    for (const ContactEvent& e : events) {
        // The event's span, at least one sample wide to be visible.
        shading += fmt::format("set object rect from {:.6f}, graph 0 to {:.6f}, graph 1 fc rgb '#ffd0d0' fs solid 0.5 noborder behind\n", e.start,
                               std::max(e.end, e.start + 0.002));
    }
    const std::string name = std::filesystem::path(title).filename().string();
    for (std::size_t j = 0; j < robot.joints.size(); ++j) {
        plot::Panel p;
        p.title = fmt::format("{}: joint {} ({})", name, j + 1, robot.joints[j].name);
        p.xlabel = "t (s)";
        p.ylabel = "external torque (N.m)";
        p.series.push_back({"estimate", replay.t, replay.external[j], "lines lw 1.5 lc rgb '#1f77b4'"});
        std::vector<double> threshold = applied_threshold(replay, monitor.thresholds[j], j), negative(threshold.size());
        for (std::size_t i = 0; i < threshold.size(); ++i) negative[i] = -threshold[i];
        p.series.push_back({"threshold", replay.t, threshold, "lines lw 1 dt 2 lc rgb '#d62728'"});
        p.series.push_back({"", replay.t, negative, "lines lw 1 dt 2 lc rgb '#d62728'"});
        // File and joint names are shown as written (gnuplot's enhanced text makes '_' a subscript).
        p.extra = shading + "set key top left\nset termoption noenhanced\n";
        panels.push_back(p);
    }
    plot::render_png(png, panels, 1100, 240);
}

std::string estimates_csv(const Replay& replay, const MonitorFile& monitor) {
    const std::size_t n = replay.external.size();
    std::string s = "t";
    for (std::size_t j = 1; j <= n; ++j) s += fmt::format(",tau_ext{}", j);
    for (std::size_t j = 1; j <= n; ++j) s += fmt::format(",threshold{}", j);
    s += "\n";
    std::vector<std::vector<double>> thresholds;
    for (std::size_t j = 0; j < n; ++j) thresholds.push_back(applied_threshold(replay, monitor.thresholds[j], j));
    for (std::size_t i = 0; i < replay.t.size(); ++i) {
        s += fmt::format("{:.6f}", replay.t[i]);
        for (std::size_t j = 0; j < n; ++j) s += fmt::format(",{:.6g}", replay.external[j][i]);
        for (std::size_t j = 0; j < n; ++j) s += fmt::format(",{:.6g}", thresholds[j][i]);
        s += "\n";
    }
    return s;
}

std::string calibration_text(const std::vector<JointCalibration>& joints, const MonitorFile& monitor, const robot::RobotDescription& robot) {
    std::string s = fmt::format("thresholds at a false-alarm rate of {:g} per sample, margin {:g} ({} estimator, {} log(s))\n", monitor.false_alarm_rate,
                                monitor.margin, to_string(monitor.estimator.estimator), monitor.calibrated_from.size());
    s += fmt::format("{:>5}  {:<16}  {:>10}  {:>10}  {:>9}  {:>9}  {:>9}\n", "joint", "name", "moving", "standing", "band", "n moving", "n standing");
    for (std::size_t j = 0; j < joints.size(); ++j) {
        const JointCalibration& c = joints[j];
        s += fmt::format("{:>5}  {:<16}  {:>10.3f}  {:>10.3f}  {:>9.3f}  {:>9}  {:>9}{}\n", j + 1, robot.joints[j].name, c.thresholds.moving, c.thresholds.standing,
                         c.max_band, c.moving_samples, c.standing_samples, c.note.empty() ? "" : "  (" + c.note + ")");
    }
    const auto& bm = monitor.band_margin;
    const bool widened = std::any_of(bm.begin(), bm.end(), [](double b) { return b > 0.0; });
    std::string factors;
    for (const double b : bm) factors += fmt::format("{}{:g}", factors.empty() ? "" : ", ", 1.0 + b);
    s += widened ? fmt::format("N.m; band: the joint's Coulomb level x {} (band margin{}), standing: beyond it, so the smallest contact "
                               "told at rest is band + standing\n", factors, bm.size() > 1 ? ", per joint" : "")
                 : "N.m; standing: beyond the joint's Coulomb band, so the smallest contact told at rest is band + standing\n";
    return s;
}

nlohmann::json calibration_json(const std::vector<JointCalibration>& joints, const MonitorFile& monitor) {
    nlohmann::json j;
    j["false_alarm_rate"] = monitor.false_alarm_rate;
    j["margin"] = monitor.margin;
    if (monitor.band_margin.size() == 1) {
        j["band_margin"] = monitor.band_margin.front();
    } else {
        j["band_margin"] = monitor.band_margin;
    }
    j["estimator"] = to_string(monitor.estimator.estimator);
    j["logs"] = monitor.calibrated_from;
    j["joints"] = nlohmann::json::array();
    for (std::size_t k = 0; k < joints.size(); ++k) {
        const JointCalibration& c = joints[k];
        j["joints"].push_back({{"joint", k + 1},
                               {"moving", c.thresholds.moving},
                               {"standing", c.thresholds.standing},
                               {"band", c.max_band},
                               {"moving_samples", c.moving_samples},
                               {"standing_samples", c.standing_samples},
                               {"note", c.note}});
    }
    return j;
}

}  // namespace jacobid::monitor
