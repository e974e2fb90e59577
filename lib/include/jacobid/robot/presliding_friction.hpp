// SPDX-License-Identifier: MIT
#pragma once
// Friction with memory: Dahl-type presliding friction (docs/method.md, "Presliding friction (Dahl)").
// When a joint stops, its drive holds a friction torque with the sign of the last motion, and that torque
// follows displacements of 1e-4 rad: a state of the position path, not of the velocity. The normalized
// state s in [-1, 1] obeys
//     ds/dx = (1 - s sgn(dx)) / x_p
// along the joint's displacement x (x_p: presliding displacement, rad); the friction torque F_d s is linear
// in the parameter F_d (FDj). Over a step dx of one sign the equation has the exact solution
//     s <- sgn(dx) + (s - sgn(dx)) exp(-|dx| / x_p),
// so the update is unconditionally stable and never leaves [-1, 1], whatever the sample period.
//
// Logged positions are quantized (the UR10e's to 1e-4 rad) and flicker by one step at rest; fed to the
// state directly, each flicker is a reversal that erases the memory. The play operator (backlash) removes
// them causally: its output moves only when the input leaves a band of half-width r around it.
//
// Allocation-free, scalar, one object per joint: usable in firmware as in the host tools.
#include <cmath>

namespace jacobid::robot {

// Causal play (backlash) operator of half-width r >= 0: y_k = min(max(y_{k-1}, x_k - r), x_k + r), started
// at the first input.
class PlayOperator {
public:
    explicit PlayOperator(double half_width = 0.0) noexcept : half_width_(half_width) {}
    double step(double x) noexcept {
        if (!started_) {
            output_ = x;
            started_ = true;
        } else if (x - half_width_ > output_) {
            output_ = x - half_width_;
        } else if (x + half_width_ < output_) {
            output_ = x + half_width_;
        }
        return output_;
    }
    double output() const noexcept { return output_; }
    void reset() noexcept { started_ = false; }

private:
    double half_width_ = 0.0;
    double output_ = 0.0;
    bool started_ = false;
};

// Dahl state along a displacement, exact per step (see above). x_p > 0.
class DahlState {
public:
    explicit DahlState(double presliding_displacement = 1e-3, double initial = 0.0) noexcept
        : displacement_(presliding_displacement), state_(initial) {}
    double step(double dx) noexcept {
        if (dx != 0.0) {
            const double direction = dx > 0.0 ? 1.0 : -1.0;
            state_ = direction + (state_ - direction) * std::exp(-std::abs(dx) / displacement_);
        }
        return state_;
    }
    double state() const noexcept { return state_; }
    void set_state(double s) noexcept { state_ = s; }

private:
    double displacement_ = 1e-3;
    double state_ = 0.0;
};

// The Dahl state driven by positions through a play operator: step(q) per sample.
class PreslidingFriction {
public:
    // The description's defaults (robot_description.hpp), so that a fixed-size array of them can be built.
    PreslidingFriction() noexcept : PreslidingFriction(3e-4, 1e-4) {}
    PreslidingFriction(double presliding_displacement, double play_half_width, double initial = 0.0) noexcept
        : play_(play_half_width), dahl_(presliding_displacement, initial) {}
    double step(double q) noexcept {
        const bool first = !started_;
        started_ = true;
        const double before = play_.output();
        const double y = play_.step(q);
        return first ? dahl_.state() : dahl_.step(y - before);
    }
    double state() const noexcept { return dahl_.state(); }

private:
    PlayOperator play_;
    DahlState dahl_;
    bool started_ = false;
};

}  // namespace jacobid::robot
