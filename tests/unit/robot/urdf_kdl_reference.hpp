// SPDX-License-Identifier: MIT
#pragma once
// The independent reference for exported URDFs: the file read by urdfdom and turned into a KDL tree the way
// kdl_parser does it (each joint at its segment's root with the joint origin as the segment's tip frame, the
// inertial moved from its <origin> frame into the link frame by KDL), without jacobid's urdf_chain; the
// torques of the chain from the root to the deepest link by KDL's ChainIdSolver_RNE, plus the joint terms
// KDL has no place for, written out here: IA qdd + FV qd + FC c(qd) + FOFF, FV and FC read from the URDF's
// <dynamics damping friction>.
#include <kdl/chain.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/tree.hpp>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Core>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "jacobid/robot/coulomb_sign.hpp"
#include "kdl_vector_copy.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::test {

inline std::string read_text_file(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Per movable joint, the terms a URDF does not carry.
struct JointTerms {
    std::vector<double> ia, foff;
    std::vector<robot::CoulombSign> coulomb;
};

class UrdfKdlReference {
public:
    explicit UrdfKdlReference(const std::string& xml) {
        const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
        if (!model) throw std::runtime_error("urdfdom rejected the URDF");
        KDL::Tree tree(model->getRoot()->name);
        std::string tip;
        int tip_depth = -1;
        add_children(tree, *model->getRoot(), 0, tip, tip_depth);
        if (!tree.getChain(model->getRoot()->name, tip, chain_)) throw std::runtime_error("KDL: no chain to " + tip);
        // The movable joints from root to tip, and their <dynamics>.
        for (const auto& segment : chain_.segments) {
            if (segment.getJoint().getType() == KDL::Joint::None) continue;
            const auto joint = model->getJoint(segment.getJoint().getName());
            names.push_back(joint->name);
            damping.push_back(joint->dynamics ? joint->dynamics->damping : 0.0);
            friction.push_back(joint->dynamics ? joint->dynamics->friction : 0.0);
        }
    }

    std::vector<std::string> names;      // movable joints, root to tip
    std::vector<double> damping, friction;  // per movable joint (0 without <dynamics>)

    Eigen::VectorXd torques(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd, const Eigen::Vector3d& gravity,
                            const JointTerms& terms) const {
        const unsigned n = chain_.getNrOfJoints();
        const KDL::JntArray kq = to_kdl(q), kqd = to_kdl(qd), kqdd = to_kdl(qdd);
        KDL::JntArray tau(n);
        KDL::ChainIdSolver_RNE solver(chain_, KDL::Vector(gravity.x(), gravity.y(), gravity.z()));
        if (solver.CartToJnt(kq, kqd, kqdd, KDL::Wrenches(chain_.getNrOfSegments(), KDL::Wrench::Zero()), tau) < 0) {
            throw std::runtime_error("KDL ChainIdSolver_RNE failed");
        }
        Eigen::VectorXd t = from_kdl(tau);
        for (Eigen::Index j = 0; j < t.size(); ++j) {
            const auto k = static_cast<std::size_t>(j);
            t[j] += terms.ia[k] * qdd[j] + damping[k] * qd[j] + friction[k] * terms.coulomb[k](qd[j]) + terms.foff[k];
        }
        return t;
    }

private:
    static KDL::Frame frame(const urdf::Pose& p) {
        double x = 0, y = 0, z = 0, w = 1;
        p.rotation.getQuaternion(x, y, z, w);
        return KDL::Frame(KDL::Rotation::Quaternion(x, y, z, w), KDL::Vector(p.position.x, p.position.y, p.position.z));
    }

    static KDL::Joint joint_of(const urdf::Joint& j) {
        const KDL::Frame origin = frame(j.parent_to_joint_origin_transform);
        const KDL::Vector axis(j.axis.x, j.axis.y, j.axis.z);
        switch (j.type) {
            case urdf::Joint::REVOLUTE:
            case urdf::Joint::CONTINUOUS: return KDL::Joint(j.name, origin.p, origin.M * axis, KDL::Joint::RotAxis);
            case urdf::Joint::PRISMATIC: return KDL::Joint(j.name, origin.p, origin.M * axis, KDL::Joint::TransAxis);
            default: return KDL::Joint(j.name, KDL::Joint::None);
        }
    }

    static KDL::RigidBodyInertia inertia_of(const urdf::Link& link) {
        if (!link.inertial) return KDL::RigidBodyInertia::Zero();
        const urdf::Inertial& i = *link.inertial;
        const KDL::Frame origin = frame(i.origin);
        // About the centre of mass in the inertial frame, rotated into the link frame (kdl_parser's workaround).
        const KDL::RigidBodyInertia rotated = origin.M * KDL::RigidBodyInertia(0.0, KDL::Vector::Zero(),
                                                                               KDL::RotationalInertia(i.ixx, i.iyy, i.izz, i.ixy, i.ixz, i.iyz));
        return KDL::RigidBodyInertia(i.mass, origin.p, rotated.getRotationalInertia());
    }

    static void add_children(KDL::Tree& tree, const urdf::Link& link, int depth, std::string& tip, int& tip_depth) {
        if (depth > tip_depth) {
            tip = link.name;
            tip_depth = depth;
        }
        for (const auto& child : link.child_links) {
            const urdf::Joint& j = *child->parent_joint;
            const KDL::Segment segment(child->name, joint_of(j), frame(j.parent_to_joint_origin_transform), inertia_of(*child));
            if (!tree.addSegment(segment, link.name)) throw std::runtime_error("KDL: cannot add segment " + child->name);
            add_children(tree, *child, depth + 1, tip, tip_depth);
        }
    }

    KDL::Chain chain_;
};

// The worst ||tau_KDL - D x|| / ||D x|| over 50 random states (|q_j| <= limits_j, |qd| <= 2, |qdd| <= 5), D the
// model's base regressor: KDL against the model with base values x.
inline double worst_relative_difference(const UrdfKdlReference& kdl, const robot::SerialRobotModel& model, const Eigen::VectorXd& x,
                                        const Eigen::Vector3d& gravity, const JointTerms& terms, const Eigen::VectorXd& limits) {
    const int n = model.joint_count();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::MatrixXd D(n, model.parameter_count());
    double worst = 0.0;
    for (int trial = 0; trial < 50; ++trial) {
        Eigen::VectorXd q(n), qd(n), qdd(n);
        for (int j = 0; j < n; ++j) {
            q[j] = limits[j] * u(rng);
            qd[j] = 2.0 * u(rng);
            qdd[j] = 5.0 * u(rng);
        }
        model.regressor(q.data(), qd.data(), qdd.data(), D);
        const Eigen::VectorXd identified = D * x;
        worst = std::max(worst, (kdl.torques(q, qd, qdd, gravity, terms) - identified).norm() / identified.norm());
    }
    return worst;
}

}  // namespace jacobid::test
