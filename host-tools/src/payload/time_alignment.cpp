// SPDX-License-Identifier: MIT
#include "payload/time_alignment.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.hpp"

namespace jacobid::payload {
namespace {

// Linear interpolation of a uniformly sampled column at time t (s from its first sample); NaN outside.
double at(const std::vector<double>& x, double period, double t) {
    const double u = t / period;
    if (u < 0.0 || u > static_cast<double>(x.size() - 1)) return std::numeric_limits<double>::quiet_NaN();
    const auto i = std::min(static_cast<std::size_t>(u), x.size() - 2);
    const double f = u - static_cast<double>(i);
    return x[i] + f * (x[i + 1] - x[i]);
}

// Mean squared position mismatch at `shift`, over every `stride`-th loaded sample the unloaded run covers;
// infinity when they overlap over less than `min_overlap` samples.
double mismatch(const identify::LogColumns& l, const identify::LogColumns& u, double shift, std::size_t stride, std::size_t min_overlap) {
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t k = 0; k < l.samples(); k += stride) {
        const double t = static_cast<double>(k) * l.sample_period + shift;
        double e = 0.0;
        bool inside = true;
        for (std::size_t j = 0; j < l.q.size() && inside; ++j) {
            const double v = at(*u.q[j], u.sample_period, t);
            if (std::isnan(v)) inside = false;
            else e += (v - (*l.q[j])[k]) * (v - (*l.q[j])[k]);
        }
        if (!inside) continue;
        sum += e;
        ++count;
    }
    return count * stride >= min_overlap ? sum / static_cast<double>(count) : std::numeric_limits<double>::infinity();
}

}  // namespace

Alignment align_runs(const identify::LogColumns& loaded, const identify::LogColumns& unloaded) {
    if (loaded.q.size() != unloaded.q.size()) {
        throw InputError(fmt::format("--unloaded {}: {} joints, but --in {} has {}", unloaded.source, unloaded.q.size(), loaded.source, loaded.q.size()));
    }
    const double tl = loaded.sample_period * static_cast<double>(loaded.samples() - 1);
    const double tu = unloaded.sample_period * static_cast<double>(unloaded.samples() - 1);
    const std::size_t min_overlap = std::min(loaded.samples(), static_cast<std::size_t>(tu / loaded.sample_period)) / 2;
    // Coarse: ~4000 shifts over every overlap of at least half the shorter run, ~2000 loaded samples each.
    const double coarse = std::max({loaded.sample_period, unloaded.sample_period, (tl + tu) / 4000.0});
    const std::size_t stride = std::max<std::size_t>(1, loaded.samples() / 2000);
    double best = 0.0, best_cost = std::numeric_limits<double>::infinity();
    for (double s = -tl; s <= tu; s += coarse) {
        const double c = mismatch(loaded, unloaded, s, stride, min_overlap);
        if (c < best_cost) best_cost = c, best = s;
    }
    if (!std::isfinite(best_cost)) {
        throw InputError(fmt::format("--unloaded {}: no shift makes it overlap --in {} over half of the shorter run: not the same trajectory?",
                                     unloaded.source, loaded.source));
    }
    // Refinement: around the best shift, ten times finer per pass down to a tenth of the loaded period, on at
    // most ~20000 samples (an hour at 1 kHz would otherwise cost 1e11 interpolations).
    Alignment a;
    a.resolution = loaded.sample_period / 10.0;
    const std::size_t fine_stride = std::max<std::size_t>(1, loaded.samples() / 20000);
    best_cost = mismatch(loaded, unloaded, best, fine_stride, min_overlap);  // comparable with the passes' costs
    for (double step = coarse; step > a.resolution;) {
        const double next = std::max(step / 10.0, a.resolution), centre = best;
        for (double s = centre - step; s <= centre + step + 0.5 * next; s += next) {
            const double c = mismatch(loaded, unloaded, s, fine_stride, min_overlap);
            if (c < best_cost) best_cost = c, best = s;
        }
        step = next;
    }
    best_cost = mismatch(loaded, unloaded, best, 1, min_overlap);
    a.shift = best;
    a.position_rms = std::sqrt(best_cost / static_cast<double>(loaded.q.size()));
    double sum = 0.0;
    for (const auto* q : loaded.q) {
        double mean = 0.0;
        for (double v : *q) mean += v;
        mean /= static_cast<double>(q->size());
        for (double v : *q) sum += (v - mean) * (v - mean);
    }
    a.motion_rms = std::sqrt(sum / static_cast<double>(loaded.q.size() * loaded.samples()));
    a.first = static_cast<std::size_t>(std::max(0.0, std::ceil(-best / loaded.sample_period)));
    a.last = std::min(loaded.samples(), static_cast<std::size_t>(std::floor((tu - best) / loaded.sample_period)) + 1);
    return a;
}

namespace {

OwnedLog owned_log(const identify::LogColumns& like, std::vector<std::vector<double>> q, std::vector<std::vector<double>> tau, double start,
                   const std::string& source) {
    OwnedLog o;
    o.q = std::move(q);
    o.tau = std::move(tau);
    const std::size_t joints = o.q.size();
    o.log = like;
    o.log.source = source;
    o.log.start_time = start;
    o.log.q.clear();
    o.log.tau.clear();
    o.log.qd.assign(joints, nullptr);
    o.log.q_ref.assign(joints, nullptr);
    o.log.qd_ref.assign(joints, nullptr);
    o.log.own_tau.clear();
    o.log.tau_aligned_by = 0.0;
    for (std::size_t j = 0; j < joints; ++j) {
        o.log.q.push_back(&o.q[j]);
        o.log.tau.push_back(&o.tau[j]);
    }
    return o;
}

}  // namespace

AlignedPair aligned_pair(const identify::LogColumns& loaded, const identify::LogColumns& unloaded, const Alignment& a) {
    const std::size_t joints = loaded.q.size();
    std::vector<std::vector<double>> ql(joints), tl(joints), qu(joints), tu(joints);
    for (std::size_t k = a.first; k < a.last; ++k) {
        const double t = static_cast<double>(k) * loaded.sample_period + a.shift;
        if (std::isnan(at(*unloaded.q[0], unloaded.sample_period, t))) continue;  // rounding at the ends: every joint alike
        for (std::size_t j = 0; j < joints; ++j) {
            ql[j].push_back((*loaded.q[j])[k]);
            tl[j].push_back((*loaded.tau[j])[k]);
            qu[j].push_back(at(*unloaded.q[j], unloaded.sample_period, t));
            tu[j].push_back(at(*unloaded.tau[j], unloaded.sample_period, t));
        }
    }
    const double start = loaded.start_time + static_cast<double>(a.first) * loaded.sample_period;
    AlignedPair p;
    p.loaded = owned_log(loaded, std::move(ql), std::move(tl), start, loaded.source);
    p.unloaded = owned_log(loaded, std::move(qu), std::move(tu), start, unloaded.source);
    return p;
}

}  // namespace jacobid::payload
