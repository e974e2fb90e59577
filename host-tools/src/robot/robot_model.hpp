// SPDX-License-Identifier: MIT
#pragma once
// Host-side robot model interface: any number of joints, any number of base parameters. The identifier
// and the simulator only see this interface; each concrete model adapts a fixed-size, allocation-free
// regressor from lib/include/jacobid/robot/.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

namespace jacobid::robot {

// How ForwardDynamics solves for qdd: the model's own O(n) articulated-body algorithm (serial robots,
// lib/include/jacobid/robot/articulated_body.hpp), or the inertia matrix M(q) by columns and a Cholesky
// solve, which every model has and which stays the reference. A model without the first uses the second.
enum class ForwardDynamicsSolver { articulated_body, inertia_matrix };

// A model's direct forward dynamics with its parameters bound once (RobotModel::articulated_body).
class DirectForwardDynamics {
public:
    virtual ~DirectForwardDynamics() = default;
    // qdd for the motor torque tau (friction included in the model) at (q, qd); false (qdd untouched) when
    // the inertia matrix at q is not positive definite. Does not allocate.
    virtual bool accelerations(const double* q, const double* qd, const double* tau, double* qdd) = 0;
};

class RobotModel {
public:
    virtual ~RobotModel() = default;
    virtual std::string model_name() const = 0;
    virtual int joint_count() const = 0;
    virtual int parameter_count() const = 0;
    virtual const std::vector<std::string>& parameter_names() const = 0;
    // D (joint_count x parameter_count) such that tau = D X. q, qd, qdd have joint_count entries.
    virtual void regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const = 0;
    // Whether regressor() (and history_columns() after it) may be called from several threads at once on
    // one object. Models are stateless, so yes; a model that keeps per-call scratch between the two calls
    // says no, and the pipeline then builds its regressor rows on one thread.
    virtual bool concurrent_regressor() const { return true; }
    // The Coulomb columns (FCj) of regressor(q, qd, qdd) in D; the other columns of D are left unspecified.
    // The identification evaluates them a second time on a velocity of their own (docs/method.md, "Coulomb
    // columns"); the default is the whole regressor, a model that can compute them alone overrides it.
    virtual void coulomb_columns(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const {
        regressor(q, qd, qdd, D);
    }
    // The columns coulomb_columns() is for: every column of the form s(qd_j) with the Coulomb sign function
    // s, which the identification evaluates on the Coulomb velocity and filters like the torque. By default the
    // FCj columns and the load-dependent FCLj ones (by name); a model with sign-function columns of its own (the diagnosis's coulomb_smoothing
    // candidates, sim/augmented_model.hpp) lists them too.
    virtual std::vector<int> coulomb_column_indices() const;

    // tau = D(q, qd, qdd) X by a route faster than the regressor, if the model has one (it then returns
    // true); the default has none and returns false, and callers use the regressor.
    virtual bool inverse_dynamics(const double* q, const double* qd, const double* qdd, const Eigen::VectorXd& X, double* tau) const {
        (void)q, (void)qd, (void)qdd, (void)X, (void)tau;
        return false;
    }

    // The articulated-body forward dynamics for the parameters X, if the model has one; the default has
    // none (nullptr), and ForwardDynamics uses the inertia matrix.
    virtual std::unique_ptr<DirectForwardDynamics> articulated_body(const Eigen::VectorXd& X) const {
        (void)X;
        return nullptr;
    }

    // Index of a parameter by name, -1 if the model has none of that name.
    int parameter_index(const std::string& name) const;

    // Friction with memory (presliding, docs/method.md "Presliding friction (Dahl)"): some columns depend on
    // the path of the positions, which a stateless regressor call cannot see. Such a model says how many
    // state values per sample it needs, integrates them once along a whole log's (raw) positions into
    // `state` (samples x history_size(), row-major), and writes its history columns from one sample's
    // values after regressor() has left them 0. Stateless models: size 0, nothing to do.
    virtual int history_size() const { return 0; }
    virtual void integrate_history(const std::vector<const std::vector<double>*>& q, std::vector<double>& state) const {
        (void)q;
        state.clear();
    }
    virtual void history_columns(const double* state, Eigen::Ref<Eigen::MatrixXd> D) const { (void)state, (void)D; }
};

// Rigid-body forward dynamics from the regressor alone (valid for every model linear in its parameters):
//   h(q, qd) = D(q, qd, 0) X,  M(q) e_j = D(q, 0, e_j) X - D(q, 0, 0) X,  qdd = M^-1 (tau - h).
// The column trick needs no model-specific code, so a new model is simulated as soon as its regressor
// exists; a model with a direct inverse dynamics (RobotModel::inverse_dynamics) is evaluated through it
// instead, the same n + 2 evaluations at a fraction of the cost. A model with an articulated-body route
// (RobotModel::articulated_body) skips M(q) altogether in accelerations() unless `solver` asks for the
// inertia matrix; inertia() and torques() are the same either way. Workspace is preallocated in the
// constructor; accelerations() does not allocate.
class ForwardDynamics {
public:
    ForwardDynamics(const RobotModel& model, Eigen::VectorXd parameters, ForwardDynamicsSolver solver = ForwardDynamicsSolver::articulated_body);
    // The solver accelerations() uses (inertia_matrix when the model has no articulated-body route).
    ForwardDynamicsSolver solver() const { return direct_ ? ForwardDynamicsSolver::articulated_body : ForwardDynamicsSolver::inertia_matrix; }
    const Eigen::VectorXd& parameters() const { return parameters_; }
    // Inertia matrix at q.
    const Eigen::MatrixXd& inertia(const double* q);
    // qdd for the torque tau at state (q, qd). False (qdd untouched) when the inertia matrix at q is not
    // positive definite: parameters no rigid body can have, e.g. an identified negative inertia.
    bool accelerations(const double* q, const double* qd, const double* tau, double* qdd);
    // tau = D(q, qd, qdd) X.
    void torques(const double* q, const double* qd, const double* qdd, double* tau);

private:
    // out = D(q, qd, qdd) X.
    void evaluate(const double* q, const double* qd, const double* qdd, Eigen::VectorXd& out);

    const RobotModel& model_;
    Eigen::VectorXd parameters_;
    Eigen::MatrixXd D_;
    Eigen::MatrixXd M_;
    Eigen::VectorXd zero_, unit_, bias_, rhs_, base_;
    Eigen::LLT<Eigen::MatrixXd> llt_;
    std::unique_ptr<DirectForwardDynamics> direct_;
};

}  // namespace jacobid::robot
