// SPDX-License-Identifier: MIT
#include "monitor/external_torque_replay.hpp"

#include <fmt/core.h>

#include <memory>

#include "core/errors.hpp"
#include "io/time_axis.hpp"
#include "jacobid/differentiator_bank.hpp"

namespace jacobid::monitor {
namespace {

constexpr std::size_t kCapacity = 512;  // taps per kernel, as the firmware's (capacity.hpp)
using Bank = DifferentiatorBank<double, kJoints, kCapacity>;

// Windows and evaluation point as given; kappa = mu = 2 weights both ends alike, a compromise between noise
// and delay (docs/method.md, "Conventions").
std::unique_ptr<Bank> make_bank(const EstimatorSettings& s, double period, bool residual) {
    auto bank = std::make_unique<Bank>();
    std::array<JointFilterConfig, kJoints> filters{};
    for (auto& f : filters) {
        for (int c = 0; c < kChannelCount; ++c) {
            KernelParams& p = f.params[static_cast<std::size_t>(c)];
            p.order = c;
            p.kappa = p.mu = 2.0;
            p.q = 2;
            p.window = c == kAcceleration && residual ? s.acceleration_window : s.velocity_window;
            p.sample_period = period;
            p.xi = s.xi;
            p.discretization = Discretization::Exact;
        }
    }
    const BankConfigResult r = bank->configure(filters);
    if (r.status != BankStatus::Ok) {
        const char* option = r.channel == kAcceleration && residual ? "--acceleration-window" : "--velocity-window";
        std::string why = describe(r.status);
        if (r.status == BankStatus::InvalidKernel) why += std::string(": ") + describe(r.kernel_status);
        throw InputError(fmt::format("{} at a sample period of {:g} s: {}", option, period, why));
    }
    return bank;
}

}  // namespace

MonitorLog monitor_log(const io::CsvTable& table, const robot::RobotDescription& robot, const std::string& time_column, double time_tolerance) {
    MonitorLog log;
    log.source = table.source();
    log.sample_period = io::check_uniform_time(table, time_column, time_tolerance).sample_period;
    log.t = table.column(time_column);
    const std::size_t n = robot.joints.size();
    bool velocities = true;
    for (std::size_t j = 0; j < n; ++j) {
        log.q.push_back(table.column(robot.joints[j].position_column));
        log.tau.push_back(table.column(robot.joints[j].torque_column));
        velocities = velocities && table.has_column(fmt::format("qd{}", j + 1));
    }
    for (std::size_t j = 0; j < n && velocities; ++j) log.qd.push_back(table.column(fmt::format("qd{}", j + 1)));
    return log;
}

Replay replay(const MonitorModel& model, const EstimatorSettings& s, const MonitorLog& log) {
    const int n = model.joints();
    const std::size_t rows = log.t.size();
    const bool residual = s.estimator == Estimator::Residual;
    const bool measured = !residual && s.measured_velocity && !log.qd.empty();
    if (!residual && !(s.gain > 0.0)) throw InputError(fmt::format("--gain {} must be > 0 (1/s)", s.gain));
    std::unique_ptr<Bank> bank;
    if (!measured) bank = make_bank(s, log.sample_period, residual);
    robot::MomentumObserver<kJoints> observer(*model.terms, model.friction, Joints::Constant(s.gain), log.sample_period);
    robot::DirectResidual<kJoints> direct(*model.terms, model.friction);

    Replay r;
    r.delay = bank ? bank->delay_seconds() : 0.0;
    r.external.assign(static_cast<std::size_t>(n), {});
    r.band.assign(static_cast<std::size_t>(n), {});
    r.standing.assign(static_cast<std::size_t>(n), {});
    Joints q = Joints::Zero(), qd = Joints::Zero(), tau = Joints::Zero();
    Bank::Output out;
    robot::ExternalTorqueEstimate<kJoints> e;
    for (std::size_t i = 0; i < rows; ++i) {
        for (int j = 0; j < n; ++j) {
            const auto js = static_cast<std::size_t>(j);
            q[j] = log.q[js][i];
            tau[j] = log.tau[js][i];
            if (measured) qd[j] = log.qd[js][i];
        }
        robot::EstimatorStatus status = robot::EstimatorStatus::Ok;
        if (measured) {
            status = observer.step(q, qd, tau, e);
        } else {
            bank->step(q, tau, out);
            if (!out.valid) continue;
            status = residual ? direct.step(out.position, out.velocity, out.acceleration, out.torque, e) : observer.step(out.position, out.velocity, out.torque, e);
        }
        // The reader refuses non-finite cells; a model that overflows on a log's states is the only way here.
        if (status != robot::EstimatorStatus::Ok) throw InputError(fmt::format("{}: row {} (t = {:g} s): the model's estimate is not finite", log.source, i + 1, log.t[i]));
        r.t.push_back(log.t[i]);
        r.row.push_back(i);
        for (int j = 0; j < n; ++j) {
            const auto js = static_cast<std::size_t>(j);
            r.external[js].push_back(e.external[j]);
            r.band[js].push_back(e.band[j]);
            r.standing[js].push_back(e.standing[js] ? 1 : 0);
        }
    }
    if (r.t.empty()) throw InputError(fmt::format("{}: {} rows are fewer than the differentiator windows need", log.source, rows));
    return r;
}

}  // namespace jacobid::monitor
