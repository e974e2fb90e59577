// SPDX-License-Identifier: MIT
#include "excite/excitation_design.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <nlopt.hpp>
#include <random>
#include <array>
#include <atomic>
#include <functional>
#include <mutex>
#include <thread>

#include "core/errors.hpp"

namespace jacobid::excite {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kStartShare = 0.8;  // of the time limit, for the random starts
constexpr int kMaxRounds = 4;        // tightening rounds after the control-rate check
// The optimizer sees the limits with this margin: a peak between its samples (20 per period of the highest
// harmonic: at most 1 - cos(pi / 20) = 1.2 % above the samples' for a pure harmonic) then rarely needs a
// tightening round.
constexpr double kMargin = 0.985;
constexpr double kFeasible = 1e-4;  // largest aggregated constraint of a result that counts as meeting the limits

struct Callbacks {
    ExcitationProblem* problem = nullptr;
    int evaluations = 0;
    // The iterate of the lowest criterion the optimizer evaluated, feasible or not (restore_into_limits starts from it).
    Eigen::VectorXd best;
    double best_f = std::numeric_limits<double>::infinity();
};

double objective(const std::vector<double>& x, std::vector<double>& grad, void* data) {
    auto* cb = static_cast<Callbacks*>(data);
    ++cb->evaluations;
    const Eigen::Map<const Eigen::VectorXd> c(x.data(), static_cast<Eigen::Index>(x.size()));
    Eigen::VectorXd g;
    const double f = cb->problem->criterion(c, grad.empty() ? nullptr : &g);
    if (!grad.empty()) Eigen::Map<Eigen::VectorXd>(grad.data(), static_cast<Eigen::Index>(grad.size())) = g;
    if (f < cb->best_f) cb->best_f = f, cb->best = c;
    return f;
}

void constraints(unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
    auto* cb = static_cast<Callbacks*>(data);
    const Eigen::Map<const Eigen::VectorXd> c(x, n);
    Eigen::MatrixXd J;
    const Eigen::VectorXd g = cb->problem->constraint_values(c, grad ? &J : nullptr);
    Eigen::Map<Eigen::VectorXd>(result, m) = g;
    // NLopt wants grad[i * n + j] = d c_i / d x_j: row-major.
    if (grad) Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(grad, m, n) = J;
}

// The largest share of its room a kinematic limit (position, velocity, acceleration) uses at c: value / room =
// g + 1 is linear in c for these kinds, so c / use meets them exactly.
double kinematic_use(ExcitationProblem& problem, const Eigen::VectorXd& c) {
    const Eigen::VectorXd g = problem.constraint_values(c, nullptr);
    double worst = 0.0;
    for (Eigen::Index r = 0; r < problem.workspace_row(); ++r) {
        if (r % kLimitKinds != static_cast<int>(LimitKind::Torque) && g[r] > -1.0) worst = std::max(worst, g[r] + 1.0);
    }
    return worst;
}

// A random start inside the kinematic limits: normal coefficients, scaled so that the largest kinematic
// constraint sits at half its room.
Eigen::VectorXd random_start(ExcitationProblem& problem, std::mt19937_64& rng) {
    std::normal_distribution<double> normal(0.0, 1.0);
    Eigen::VectorXd c(problem.variables());
    for (Eigen::Index i = 0; i < c.size(); ++i) c[i] = normal(rng) / (1.0 + static_cast<double>(i % problem.basis().size() / 2));
    const double worst = kinematic_use(problem, c);
    if (worst > 0.0) c *= 0.5 / worst;
    // The workspace faces are not linear in c, but c = 0 (at rest at the pose) is strictly inside the box:
    // halve the motion until the point keeps half of every face's room (at most 10 times).
    for (int halving = 0; problem.workspace() && halving < 10; ++halving) {
        if (problem.constraint_values(c, nullptr).tail(kBoxFaces).maxCoeff() <= -0.5) break;
        c *= 0.5;
    }
    return c;
}

// Every face's room scaled by `factor(face)`: the user's box seen by the optimizer.
template <typename Factor>
WorkspaceBox scaled_box(const Workspace& workspace, const WorkspaceBox& box, Factor factor) {
    std::array<double, kBoxFaces> factors{};
    for (int f = 0; f < kBoxFaces; ++f) factors[static_cast<std::size_t>(f)] = factor(f);
    return shrink_toward(box, workspace.start, factors);
}

struct LocalResult {
    Eigen::VectorXd c;
    double f = std::numeric_limits<double>::infinity();
    double violation = std::numeric_limits<double>::infinity();
};

// c with its criterion and its largest constraint.
LocalResult judged(ExcitationProblem& problem, const Eigen::VectorXd& c) {
    LocalResult r;
    r.c = c;
    r.f = problem.criterion(c, nullptr);
    r.violation = problem.constraint_values(c, nullptr).maxCoeff();
    return r;
}

// One optimizer run from `start` (MMA for the information criteria, SLSQP for cond and logdet); cb receives the
// lowest-criterion iterate it evaluated.
LocalResult optimizer_run(ExcitationProblem& problem, const Eigen::VectorXd& start, double seconds, int max_evaluations, int& evaluations, Callbacks& cb) {
    const auto n = static_cast<unsigned>(problem.variables());
    // The information criteria pull hard toward the limits: SLSQP's linearized steps then left half the PUMA 560's
    // starts wandering outside them (-603 and -774 where others reached -1013 in d-optimal, 30 s), while Svanberg's
    // MMA, whose conservative approximations keep the iterates inside, reached -1015 from every start. The
    // column-scaled criteria keep SLSQP (their figures in docs/excite.md were made with it).
    nlopt::opt opt(is_information_criterion(problem.criterion_kind()) ? nlopt::LD_MMA : nlopt::LD_SLSQP, n);
    opt.set_min_objective(objective, &cb);
    if (is_information_criterion(problem.criterion_kind())) {
        // MMA solves a dual problem (one variable per constraint) at every evaluation. NLopt's default for it,
        // another MMA to a relative 1e-14 with up to 100 000 steps, took 96 % of a PUMA 560 design's time (perf:
        // ~0.24 s per evaluation inside NLopt against 10 ms in the criterion). L-BFGS to 1e-10 solves the same
        // small concave dual: that design 16 min -> 35 s, the UR5-like arm's 153 s -> 12 s, criteria as good or
        // better (docs/excite.md, "Speed"). NLopt takes only the algorithm, tolerances and budget from this
        // optimizer; its dimension must match the problem's.
        nlopt::opt dual(nlopt::LD_LBFGS, n);
        dual.set_ftol_rel(1e-10);
        dual.set_maxeval(2000);
        opt.set_local_optimizer(dual);
    }
    opt.add_inequality_mconstraint(constraints, &cb, std::vector<double>(static_cast<std::size_t>(problem.constraints()), 1e-6));
    opt.set_ftol_rel(1e-7);
    opt.set_xtol_rel(1e-7);
    opt.set_maxeval(max_evaluations);
    opt.set_maxtime(std::max(seconds, 0.5));
    std::vector<double> x(start.data(), start.data() + start.size());
    double f = 0.0;
    try {
        opt.optimize(x, f);
    } catch (const nlopt::roundoff_limited&) {
        // SLSQP stopped at rounding: x is its last iterate, as good as it gets.
    } catch (const nlopt::forced_stop&) {
    } catch (const std::runtime_error&) {
        // "nlopt failure" (e.g. an infeasible linearization): the last iterate is still judged below.
    }
    evaluations += cb.evaluations;
    return judged(problem, Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size())));
}

// A point the optimizer reached outside the limits brought back inside: scaled onto the kinematic limits (homogeneous in
// c), then halved while a torque limit or the workspace box is still crossed (at most 6 times); empty when none is found.
Eigen::VectorXd restore_into_limits(ExcitationProblem& problem, Eigen::VectorXd c) {
    const double use = kinematic_use(problem, c);
    if (use > 0.0) c *= std::min(1.0, 0.99 / use);
    for (int halving = 0; halving < 6; ++halving) {
        if (problem.constraint_values(c, nullptr).maxCoeff() <= kFeasible) return c;
        c *= 0.5;
    }
    return {};
}

// The optimizer from `start`. A run that ends outside the limits counts as its end point brought back inside
// (MMA can converge onto a face from just outside it: +2e-4 on the 2R's workspace box, which had used the whole
// time); a run that ends outside or where it began (SLSQP on an information criterion did, MMA rarely does)
// restarts from its best iterate brought back inside, while time is left (at most 3 runs). The best feasible
// point of all runs is the result.
LocalResult local_run(ExcitationProblem& problem, const Eigen::VectorXd& start, double seconds, int max_evaluations, int& evaluations) {
    const auto begin = Clock::now();
    auto left = [&] { return seconds - std::chrono::duration<double>(Clock::now() - begin).count(); };
    LocalResult best;
    Eigen::VectorXd from = start;
    for (int run = 0; run < 3 && from.size() > 0; ++run) {
        Callbacks cb;
        cb.problem = &problem;
        const LocalResult reached = optimizer_run(problem, from, run == 0 ? seconds : left(), max_evaluations, evaluations, cb);
        LocalResult r = reached;
        if (!(reached.violation <= kFeasible)) {
            const Eigen::VectorXd inside = restore_into_limits(problem, reached.c);
            if (inside.size() > 0) r = judged(problem, inside);
        }
        const bool best_feasible = best.violation <= kFeasible;
        if (r.violation <= kFeasible ? (!best_feasible || r.f < best.f) : (!best_feasible && r.violation < best.violation)) best = r;
        const bool stalled = !(reached.violation <= kFeasible) || (reached.c - from).norm() <= 1e-9 * std::max(1.0, from.norm());
        if (!stalled || left() < 0.5 || cb.best.size() == 0) break;
        from = restore_into_limits(problem, cb.best);
        if (from.size() == 0 || (best.violation <= kFeasible && problem.criterion(from, nullptr) >= best.f)) break;
    }
    return best;
}

// The limits the optimizer sees: the user's, kMargin inside them around the pose.
std::vector<JointLimits> with_margin(const std::vector<JointLimits>& limits, const Eigen::VectorXd& pose) {
    std::vector<JointLimits> tightened = limits;
    for (std::size_t j = 0; j < tightened.size(); ++j) {
        JointLimits& l = tightened[j];
        const double p = pose[static_cast<Eigen::Index>(j)];
        l.upper = p + (l.upper - p) * kMargin;
        l.lower = p - (p - l.lower) * kMargin;
        l.velocity *= kMargin, l.acceleration *= kMargin, l.torque *= kMargin;
    }
    return tightened;
}

// Each limit that the control-rate check found exceeded, tightened by its overshoot plus 1 %.
void tighten_by_overshoot(std::vector<JointLimits>& tightened, const Eigen::VectorXd& pose, const LimitCheck& check) {
    for (std::size_t j = 0; j < tightened.size(); ++j) {
        JointLimits& l = tightened[j];
        const double p = pose[static_cast<Eigen::Index>(j)];
        auto shrink = [&](int kind) { return 1.0 / (1.01 * std::max(1.0, check.ratio(static_cast<Eigen::Index>(j), kind))); };
        l.upper = p + (l.upper - p) * shrink(0);
        l.lower = p - (p - l.lower) * shrink(1);
        l.velocity *= shrink(2);
        l.acceleration *= shrink(3);
        l.torque *= shrink(4);
    }
}

// The random starts on `threads` workers, each with its own copy of the problem (its caches are per instance;
// the model's regressor is const). Start s draws from seed + s, so the result does not depend on the threads.
// Returns the best feasible result; fills d's starts_run, start_criteria and evaluations.
LocalResult best_of_starts(const ExcitationProblem& problem, const DesignSettings& settings, const std::function<double()>& elapsed,
                           const std::function<void(const std::string&)>& say, Design& d) {
    const int workers = std::max(1, std::min(settings.threads, settings.starts));
    const int rounds_of_starts = (settings.starts + workers - 1) / workers;
    std::vector<LocalResult> results(static_cast<std::size_t>(settings.starts));
    std::vector<int> evaluations(static_cast<std::size_t>(workers), 0);
    std::vector<bool> ran(static_cast<std::size_t>(settings.starts), false);
    std::atomic<int> next{0};
    std::mutex report;
    auto worker = [&](int w) {
        ExcitationProblem local = problem;
        for (int s = next++; s < settings.starts; s = next++) {
            // The starts share 80 % of the time; the rest is kept for the tightening rounds.
            const double remaining = kStartShare * settings.time_limit - elapsed();
            if (remaining <= 0.0 && s >= workers) break;
            const int left_here = rounds_of_starts - s / workers;
            const double budget = remaining / std::max(1, left_here);
            std::mt19937_64 rng(settings.seed + static_cast<std::uint64_t>(s));
            int& count = evaluations[static_cast<std::size_t>(w)];
            Eigen::VectorXd start = random_start(local, rng);
            // The relative criteria (a sum or a max of ratios spanning decades) stall from a random start far from
            // the limits: each start first maximizes the information (d-optimal) for half its time, then refines.
            const Criterion wanted = local.criterion_kind();
            const bool warm = wanted == Criterion::ARelative || wanted == Criterion::ERelative || wanted == Criterion::IOptimal;
            if (warm) {
                local.set_criterion(Criterion::DOptimal);
                start = local_run(local, start, budget / 2, settings.max_evaluations, count).c;
                local.set_criterion(wanted);
            }
            LocalResult r = local_run(local, start, warm ? budget / 2 : budget, settings.max_evaluations, count);
            const double cond = local.condition_number(r.c);
            const std::lock_guard<std::mutex> lock(report);
            say(fmt::format("start {}/{}: {} {:.4g}, cond {:.4g}, largest constraint {:+.2e}{} ({:.1f} s)", s + 1, settings.starts,
                            to_string(problem.criterion_kind()), r.f, cond, r.violation,
                            r.violation <= kFeasible ? "" : " (infeasible)", elapsed()));
            results[static_cast<std::size_t>(s)] = std::move(r);
            ran[static_cast<std::size_t>(s)] = true;
        }
    };
    std::vector<std::thread> pool;
    for (int w = 1; w < workers; ++w) pool.emplace_back(worker, w);
    worker(0);
    for (auto& t : pool) t.join();
    LocalResult best;
    for (int s = 0; s < settings.starts; ++s) {
        if (!ran[static_cast<std::size_t>(s)]) continue;
        const LocalResult& r = results[static_cast<std::size_t>(s)];
        ++d.starts_run;
        const bool feasible = r.violation <= kFeasible;
        d.start_criteria.push_back(feasible ? r.f : std::numeric_limits<double>::quiet_NaN());
        if (feasible && r.f < best.f) best = r;
    }
    for (const int e : evaluations) d.evaluations += e;
    if (!std::isfinite(best.f)) {
        throw InputError(fmt::format("excite: no start met the limits ({} starts; the pose's gravity torque or the limits may leave no room)", d.starts_run));
    }
    return best;
}

}  // namespace

Design design_excitation(ExcitationProblem& problem, const robot::RobotModel& model, const Eigen::VectorXd& parameters,
                         const std::vector<JointLimits>& limits, const DesignSettings& settings) {
    const auto start_time = Clock::now();
    const std::function<double()> elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start_time).count(); };
    const std::function<void(const std::string&)> say = [&](const std::string& line) {
        if (settings.progress) settings.progress(line);
    };
    Design d;
    std::vector<JointLimits> tightened = with_margin(limits, problem.pose());
    problem.set_limits(tightened);
    // The workspace box (if any) with the same margin; `box` is the user's.
    const std::optional<WorkspaceBox> box = problem.workspace() ? std::optional<WorkspaceBox>(problem.workspace()->box) : std::nullopt;
    if (box) problem.set_workspace_box(scaled_box(*problem.workspace(), *box, [](int) { return kMargin; }));
    LocalResult best = best_of_starts(problem, settings, elapsed, say, d);
    // Every control sample: a limit missed between the optimizer's samples tightens that limit by the
    // overshoot (plus 1 %) and re-optimizes from the best point.
    // The workspace point too, against the user's box.
    auto check_workspace_box = [&]() -> double {
        if (!box) return 0.0;
        Workspace user = *problem.workspace();
        user.box = *box;
        d.workspace = check_workspace(user, problem.trajectory(best.c), settings.control_rate);
        return d.workspace->worst;
    };
    for (;;) {
        d.check = check_limits(model, parameters, problem.trajectory(best.c), limits, settings.control_rate);
        const double box_worst = check_workspace_box();
        if ((d.check.worst <= 1.0 && box_worst <= 1.0) || d.rounds >= kMaxRounds) break;
        ++d.rounds;
        if (box_worst > d.check.worst) {
            say(fmt::format("round {}: the workspace point at {:.4g} of the box's {} face between the optimizer's samples; tightened, re-optimizing", d.rounds,
                            box_worst, face_name(d.workspace->worst_face)));
        } else {
            say(fmt::format("round {}: joint {} {} at {:.4g} of its limit between the optimizer's samples; tightened, re-optimizing", d.rounds,
                            d.check.worst_joint + 1, to_string(d.check.worst_kind), d.check.worst));
        }
        if (box) {
            const WorkspaceBox seen = problem.workspace()->box;
            problem.set_workspace_box(scaled_box(*problem.workspace(), seen, [&](int f) {
                return 1.0 / (1.01 * std::max(1.0, d.workspace->ratio[static_cast<std::size_t>(f)]));
            }));
        }
        tighten_by_overshoot(tightened, problem.pose(), d.check);
        problem.set_limits(tightened);
        const double left = std::max(2.0, (settings.time_limit - elapsed()) / (kMaxRounds - d.rounds + 1));
        const LocalResult r = local_run(problem, best.c, left, settings.max_evaluations, d.evaluations);
        if (r.violation <= kFeasible) best = r;
    }
    if (box) problem.set_workspace_box(*box);
    if (d.workspace && d.workspace->worst > 1.0) {
        throw InputError(fmt::format("excite: the workspace point reaches {:.4g} of the box's {} face at t = {:.4g} s between the optimizer's samples (use more --samples)",
                                     d.workspace->worst, face_name(d.workspace->worst_face),
                                     static_cast<double>(d.workspace->worst_sample) / settings.control_rate));
    }
    if (d.check.worst > 1.0) {
        throw InputError(fmt::format("excite: joint {} {} reaches {:.4g} of its limit at t = {:.4g} s between the optimizer's samples (use more --samples)",
                                     d.check.worst_joint + 1, to_string(d.check.worst_kind), d.check.worst,
                                     static_cast<double>(d.check.worst_sample) / settings.control_rate));
    }
    d.coefficients = best.c;
    d.criterion = best.f;
    d.cond = problem.condition_number(best.c);
    d.seconds = elapsed();
    return d;
}

}  // namespace jacobid::excite
