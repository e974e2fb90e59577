// SPDX-License-Identifier: MIT
#include "monitor/contact_events.hpp"

#include <algorithm>
#include <cmath>

namespace jacobid::monitor {
namespace {

robot::ExternalTorqueEstimate<kJoints> estimate_at(const Replay& r, std::size_t i) {
    robot::ExternalTorqueEstimate<kJoints> e;
    for (std::size_t j = 0; j < r.external.size(); ++j) {
        const auto jj = static_cast<Eigen::Index>(j);
        e.external[jj] = r.external[j][i];
        e.band[jj] = r.band[j][i];
        e.standing[j] = r.standing[j][i] != 0;
    }
    return e;
}

}  // namespace

std::vector<double> applied_threshold(const Replay& replay, const robot::JointThresholds& thresholds, std::size_t joint) {
    std::vector<double> out(replay.t.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        out[i] = replay.standing[joint][i] ? replay.band[joint][i] + thresholds.standing : thresholds.moving;
    }
    return out;
}

std::vector<ContactEvent> contact_events(const Replay& r, const std::vector<robot::JointThresholds>& thresholds, double hold, int confirm) {
    const int n = static_cast<int>(r.external.size());
    robot::ContactDetector<kJoints> detector;
    detector.set_confirm(confirm);
    for (int j = 0; j < n; ++j) detector.set_joint(j, thresholds[static_cast<std::size_t>(j)]);
    std::vector<ContactEvent> events;
    bool open = false;
    std::uint32_t joints = 0;
    auto close = [&] {
        ContactEvent& e = events.back();
        for (int j = 0; j < n; ++j) {
            if (joints & (1u << j)) e.joints.push_back(j);
        }
        // Peaks over the event, every joint (a push on one joint moves the others' estimates too).
        e.peak.assign(static_cast<std::size_t>(n), 0.0);
        e.peak_time.assign(static_cast<std::size_t>(n), e.start);
        std::vector<std::vector<double>> values(static_cast<std::size_t>(n));
        for (std::size_t i = 0; i < r.t.size(); ++i) {
            if (r.t[i] < e.start || r.t[i] > e.end) continue;
            for (std::size_t j = 0; j < static_cast<std::size_t>(n); ++j) {
                values[j].push_back(r.external[j][i]);
                if (std::abs(r.external[j][i]) > std::abs(e.peak[j])) {
                    e.peak[j] = r.external[j][i];
                    e.peak_time[j] = r.t[i];
                }
            }
        }
        for (auto& v : values) {
            std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
            e.median.push_back(v[v.size() / 2]);
        }
        open = false;
        joints = 0;
    };
    for (std::size_t i = 0; i < r.t.size(); ++i) {
        const std::uint32_t mask = detector.detect(estimate_at(r, i), n);
        const bool confirmed = detector.confirmed(mask);
        if (open && mask == 0 && r.t[i] - events.back().end >= hold) close();
        if (mask == 0 || (!open && !confirmed)) continue;
        if (!open) {
            events.push_back({});
            events.back().start = r.t[i];
            open = true;
        }
        events.back().end = r.t[i];
        joints |= mask;
    }
    if (open) close();
    return events;
}

}  // namespace jacobid::monitor
