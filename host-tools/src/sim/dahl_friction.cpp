// SPDX-License-Identifier: MIT
#include "sim/dahl_friction.hpp"

#include "robot/presliding_model.hpp"
#include "sim/augmented_model.hpp"

namespace jacobid::sim {

void DahlFriction::add(int joint, double displacement, double level) {
    joint_.push_back(joint);
    dahl_.emplace_back(displacement);
    level_.push_back(level);
}

void DahlFriction::step(const Eigen::VectorXd& before, const Eigen::VectorXd& after, Eigen::VectorXd& torque) {
    torque.setZero();
    for (std::size_t i = 0; i < dahl_.size(); ++i) {
        const auto je = static_cast<Eigen::Index>(joint_[i]);
        torque[je] += level_[i] * dahl_[i].step(after[je] - before[je]);
    }
}

std::unique_ptr<DahlFriction> presliding_friction(const robot::RobotModel& model, const Eigen::VectorXd& parameters) {
    auto dahl = std::make_unique<DahlFriction>();
    const auto* augmented = dynamic_cast<const AugmentedModel*>(&model);
    if (const auto* presliding = dynamic_cast<const robot::PreslidingModel*>(augmented ? &augmented->nominal() : &model)) {
        for (int j = 0; j < presliding->joint_count(); ++j) {
            dahl->add(j, presliding->settings().displacement[static_cast<std::size_t>(j)], parameters[presliding->first_presliding_column() + j]);
        }
    }
    if (augmented) {
        for (std::size_t t = 0; t < augmented->terms().size(); ++t) {
            const EffectTerm& term = augmented->terms()[t];
            if (term.kind == EffectKind::Presliding) dahl->add(term.joint, term.displacement, parameters[augmented->term_column(t)]);
        }
    }
    return dahl->empty() ? nullptr : std::move(dahl);
}

}  // namespace jacobid::sim
