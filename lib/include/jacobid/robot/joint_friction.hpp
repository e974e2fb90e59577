// SPDX-License-Identifier: MIT
#pragma once
// The identified friction of each joint as the external-torque estimator subtracts it (docs/method.md,
// "External torque and contact detection"):
//     f = FV qd + (FC + FCL l(g)) s(qd) + FOFF + FD z,
// and, when the joint stands (|qd| below standing_velocity), its Coulomb band FC: at rest friction holds ANY
// torque in [-FC, FC], whatever the model's s(0) = 0 says. A joint at rest with a torque inside its band is
// friction doing its job, not a contact: the UR10e's wrists hold several N.m after each stop. The band goes
// to the detector, which adds it to its standing threshold (contact_detector.hpp); f itself stays the
// model's, continuous through the standing velocity (dropping FC s(qd) there would step the estimate by up to
// FC s(standing_velocity), 70 % of FC at alpha = 100 s/rad and 0.02 rad/s: a false alarm at every stop).
// z is the Dahl presliding state (presliding_friction.hpp) driven by the positions, when FD is identified.
// FCL l(g) is the load-dependent Coulomb level (`friction: coulomb_load`, docs/method.md "Load-dependent Coulomb
// friction"): l = |g| (abs) or g^2 (square) of the joint's gravity torque under the model's own parameters (the
// reference the host's LoadFrictionModel takes for a description), when FCL is identified; at standstill the band
// is the whole Coulomb level FC + FCL l(g), the friction a loaded joint holds. With presliding the sliding level is
// FC + FD (z saturates at +-1), so a standing joint holds up to that, while the model says FD z: the band is
// FC + FCL l(g) + |FD| (1 + |z|), what the residual held - FD z can reach. The band is that level times
// (1 + band_margin): a joint breaks away above its sliding Coulomb level (static friction), by an amount the
// sliding fit cannot see (UR10e joint 1 holds 16 % above FC before it slips, docs/real-data.md).
// Fixed-size, allocation-free.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

#include "jacobid/robot/presliding_friction.hpp"
#include "jacobid/robot/rnea_regressor.hpp"

namespace jacobid::robot {

struct JointFrictionParameters {
    double viscous = 0.0;    // FV, N.m s/rad
    double coulomb = 0.0;    // FC, N.m
    double offset = 0.0;     // FOFF, N.m
    double presliding = 0.0;  // FD, N.m (0: no presliding term)
    double load = 0.0;        // FCL, N.m per N.m of gravity torque (abs) or per (N.m)^2 (square); 0: none
    bool load_square = false;  // the law: false |g|, true g^2
    double presliding_displacement = 3e-4;  // x_p, rad
    double presliding_play = 2e-4;          // rad, total width of the play operator
    CoulombSign sign{};
    double standing_velocity = 0.02;  // rad/s: |qd| below this ...
    // ... for this many consecutive samples is standstill: a velocity reversal in the middle of a motion
    // passes through 0 too, with the acceleration (and the model's error) at its largest, and friction holds
    // nothing there.
    int standing_samples = 1;
    double band_margin = 0.0;  // the band is (1 + band_margin) x the Coulomb level (break-away above sliding)
};

template <int N>
class JointFriction {
public:
    using Joints = JointVector<N>;

    JointFriction() noexcept = default;
    // The FV, FC, FOFF of standard parameters X in `regressor`'s layout, its Coulomb sign per joint.
    JointFriction(const RneaRegressor<N>& regressor, const typename RneaRegressor<N>::Parameters& X) noexcept : joints_(regressor.joint_count()) {
        const auto& layout = regressor.layout();
        for (int j = 0; j < joints_; ++j) {
            JointFrictionParameters& p = parameters_[static_cast<std::size_t>(j)];
            p.viscous = X[layout.column(j, ParameterKind::FV)];
            p.coulomb = std::abs(X[layout.column(j, ParameterKind::FC)]);
            const int offset = layout.column(j, ParameterKind::FOFF);
            p.offset = offset >= 0 ? X[offset] : 0.0;
            p.sign = regressor.coulomb(j);
        }
        reset();
    }

    void set_joint(int j, const JointFrictionParameters& p) noexcept {
        parameters_[static_cast<std::size_t>(j)] = p;
        presliding_[static_cast<std::size_t>(j)] = PreslidingFriction(p.presliding_displacement, 0.5 * p.presliding_play);
    }
    const JointFrictionParameters& joint(int j) const noexcept { return parameters_[static_cast<std::size_t>(j)]; }
    int joint_count() const noexcept { return joints_; }

    // Forgets the presliding states (each starts at 0, the neutral value, at the next step) and the standstill.
    void reset() noexcept {
        still_.fill(0);
        for (int j = 0; j < joints_; ++j) {
            const JointFrictionParameters& p = parameters_[static_cast<std::size_t>(j)];
            presliding_[static_cast<std::size_t>(j)] = PreslidingFriction(p.presliding_displacement, 0.5 * p.presliding_play);
        }
    }

    // Whether some joint has a load-dependent Coulomb term (its caller then passes the gravity torques).
    bool load_dependent() const noexcept {
        for (int j = 0; j < joints_; ++j) {
            if (parameters_[static_cast<std::size_t>(j)].load != 0.0) return true;
        }
        return false;
    }

    // One sample: advances the presliding states along q, then the friction f and, per joint, the Coulomb
    // band (the Coulomb level at standstill, 0 when moving) and whether the joint stands. `gravity`: the
    // model's gravity torques at q, needed when load_dependent() (null: no load-dependent term).
    void step(const Joints& q, const Joints& qd, Joints& f, Joints& band, std::array<bool, N>& standing, const Joints* gravity = nullptr) noexcept {
        f.setZero();
        band.setZero();
        for (int j = 0; j < joints_; ++j) {
            const auto js = static_cast<std::size_t>(j);
            const JointFrictionParameters& p = parameters_[js];
            const double z = presliding_[js].step(q[j]);
            int& still = still_[js];
            still = std::abs(qd[j]) < p.standing_velocity ? std::min(still + 1, p.standing_samples) : 0;
            standing[js] = still >= p.standing_samples;
            double coulomb = p.coulomb;
            if (gravity != nullptr && p.load != 0.0) {
                const double g = (*gravity)[j];
                coulomb += p.load * (p.load_square ? g * g : std::abs(g));
            }
            f[j] = p.offset + p.presliding * z + p.viscous * qd[j] + coulomb * p.sign(qd[j]);
            if (standing[js]) band[j] = (1.0 + p.band_margin) * (coulomb + std::abs(p.presliding) * (1.0 + std::abs(z)));
        }
    }

private:
    int joints_ = 0;
    std::array<JointFrictionParameters, N> parameters_{};
    std::array<PreslidingFriction, N> presliding_{};
    std::array<int, N> still_{};  // consecutive samples below the standing velocity (up to standing_samples)
};

}  // namespace jacobid::robot
