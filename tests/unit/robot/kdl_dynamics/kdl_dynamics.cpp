// SPDX-License-Identifier: MIT
#include "kdl_dynamics.hpp"

#include <kdl/chain.hpp>
#include <kdl/chainfdsolver_recursive_newton_euler.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>

namespace jacobid::test {
namespace {

KDL::Chain make_chain(const std::vector<KdlLink>& links) {
    KDL::Chain chain;
    for (const KdlLink& link : links) {
        const auto& p = link.inertial;
        const double m = p[9];
        // Standard parameters are about the link origin; KDL wants the mass, the centre of mass and the
        // inertia about it. A massless link has no first moment either (c is then arbitrary: 0).
        const double cx = m > 0.0 ? p[6] / m : 0.0, cy = m > 0.0 ? p[7] / m : 0.0, cz = m > 0.0 ? p[8] / m : 0.0;
        const double c2 = cx * cx + cy * cy + cz * cz;
        const KDL::RotationalInertia central(p[0] - m * (c2 - cx * cx), p[3] - m * (c2 - cy * cy), p[5] - m * (c2 - cz * cz), p[1] + m * cx * cy,
                                             p[2] + m * cx * cz, p[4] + m * cy * cz);
        const KDL::RigidBodyInertia inertia(m, KDL::Vector(cx, cy, cz), central);
        const auto& r = link.rotation;
        const KDL::Rotation rotation(r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8]);
        const KDL::Vector origin(link.position[0], link.position[1], link.position[2]);
        const KDL::Vector axis = rotation * KDL::Vector(link.axis[0], link.axis[1], link.axis[2]);  // in the antecedent frame
        // Joint at the segment root, tip = the fixed transform, so root -> tip is Fixed * Motion(q).
        const KDL::Joint joint(origin, axis, link.prismatic ? KDL::Joint::TransAxis : KDL::Joint::RotAxis, 1.0, 0.0, link.rotor_inertia);
        chain.addSegment(KDL::Segment(joint, KDL::Frame(rotation, origin), inertia));
    }
    return chain;
}

}  // namespace

struct KdlDynamics::Impl {
    Impl(const std::vector<KdlLink>& links, const std::array<double, 3>& g)
        : chain(make_chain(links)),
          gravity(g[0], g[1], g[2]),
          id(chain, gravity),
          fd(chain, gravity),  // keeps a reference to `chain`, declared before it
          q(chain.getNrOfJoints()),
          qd(chain.getNrOfJoints()),
          in(chain.getNrOfJoints()),
          out(chain.getNrOfJoints()),
          wrenches(chain.getNrOfSegments(), KDL::Wrench::Zero()) {}
    KDL::Chain chain;
    KDL::Vector gravity;
    KDL::ChainIdSolver_RNE id;
    KDL::ChainFdSolver_RNE fd;
    KDL::JntArray q, qd, in, out;
    KDL::Wrenches wrenches;

    void load(const double* q_, const double* qd_, const double* in_) {
        for (unsigned j = 0; j < chain.getNrOfJoints(); ++j) q(j) = q_[j], qd(j) = qd_[j], in(j) = in_[j];
    }
    void store(double* out_) const {
        for (unsigned j = 0; j < chain.getNrOfJoints(); ++j) out_[j] = out(j);
    }
};

KdlDynamics::KdlDynamics(const std::vector<KdlLink>& links, const std::array<double, 3>& gravity)
    : impl_(std::make_unique<Impl>(links, gravity)) {}
KdlDynamics::~KdlDynamics() = default;

int KdlDynamics::joint_count() const { return static_cast<int>(impl_->chain.getNrOfJoints()); }

bool KdlDynamics::inverse_dynamics(const double* q, const double* qd, const double* qdd, double* tau) {
    impl_->load(q, qd, qdd);
    if (impl_->id.CartToJnt(impl_->q, impl_->qd, impl_->in, impl_->wrenches, impl_->out) < 0) return false;
    impl_->store(tau);
    return true;
}

bool KdlDynamics::forward_dynamics(const double* q, const double* qd, const double* tau, double* qdd) {
    impl_->load(q, qd, tau);
    if (impl_->fd.CartToJnt(impl_->q, impl_->qd, impl_->in, impl_->wrenches, impl_->out) < 0) return false;
    impl_->store(qdd);
    return true;
}

}  // namespace jacobid::test
