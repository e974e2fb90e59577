// SPDX-License-Identifier: MIT
#pragma once
// Standard parameters that are physically possible by construction (docs/method.md, "Physically consistent
// identification"). Every link's ten inertial parameters (XX XY XZ YY YZ ZZ MX MY MZ M, about the link
// frame's origin) come from unconstrained variables:
//  - Full (identify --physical): the pseudo-inertia J = [[Sigma, h], [h^T, m]], Sigma = tr(I)/2 1 - I, h the
//    first moments, is J = U U^T with U upper triangular and a positive (exponential) diagonal: J positive
//    definite, which is exactly "a mass distribution exists" (Wensing, Kim, Slotine 2017: positive mass,
//    positive definite inertia about the centre of mass, and the triangle inequalities);
//  - Semi (identify --semi-physical): m = exp(a), the centre of mass c free, the inertia about it
//    I_c = L L^T (lower triangular, positive diagonal): positive mass and a positive definite I_c, without
//    the triangle inequalities.
// Rotor inertias (IA), viscous (FV), Coulomb (FC) and Dahl presliding (FD) coefficients are exp(b) >= 0; offsets (FOFF) and kinds
// this file does not know are free. The log-Cholesky form (Rucker and Wensing 2022) gives the nearest
// possible point of any standard vector (the interior point's start) and random bodies for tests; the
// constraints themselves go to the solver as linear matrix inequalities (constraint_blocks).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "identify/physical/lmi_barrier.hpp"

namespace jacobid::identify {

enum class PhysicalConstraint { Full, Semi };
const char* to_string(PhysicalConstraint c);

class PhysicalParametrization {
public:
    // standard_names: the model's standard parameter names (XX1 XY1 ... FC1 [FOFF1] XX2 ...); a link is a
    // complete group XXj .. Mj. std::invalid_argument when a link's group is incomplete.
    PhysicalParametrization(const std::vector<std::string>& standard_names, PhysicalConstraint constraint);

    PhysicalConstraint constraint() const { return constraint_; }
    int standard_count() const { return standard_count_; }
    int variable_count() const { return variable_count_; }
    int link_count() const { return static_cast<int>(links_.size()); }
    // Link j's standard column of XXj (its ten inertial columns follow in the XX .. M order).
    int link_first_column(int link) const { return links_[static_cast<std::size_t>(link)].first_column; }

    // The standard parameters of the variables.
    Eigen::VectorXd standard(const Eigen::VectorXd& variables) const;
    // Variables of the feasible point nearest to `standard`: each link's pseudo-inertia (Full) or I_c (Semi)
    // with its eigenvalues raised to at least `margin` times the largest (and to an absolute floor), a
    // non-positive mass raised likewise, non-negative kinds raised to `floor`. standard(variables(s)) == s
    // for a point strictly inside.
    Eigen::VectorXd variables(const Eigen::VectorXd& standard, double margin = 1e-6, double floor = 1e-9) const;

    // Smallest eigenvalue of link j's constrained matrix (J for Full, I_c for Semi) over its largest, and the
    // mass, at the given standard parameters: the constraint's distance to its boundary.
    double link_relative_min_eigenvalue(const Eigen::VectorXd& standard, int link) const;
    // The constraints as linear matrix inequalities in the standard parameters, every block positive definite:
    // per link J(s) (Full) or [[I, S(h)^T], [S(h), m 1]] (Semi: by the Schur complement, m > 0 and
    // I_c = I - S(h)^T S(h) / m positive definite), and a 1x1 block per non-negative column.
    std::vector<LmiBlock> constraint_blocks() const;
    // Standard columns that must be non-negative (IA, FV, FC, FD).
    const std::vector<int>& nonnegative_columns() const { return nonnegative_; }

private:
    struct Link {
        int first_column = 0;    // XXj
        int first_variable = 0;  // its 10 variables
    };
    PhysicalConstraint constraint_;
    int standard_count_ = 0;
    int variable_count_ = 0;
    std::vector<Link> links_;
    std::vector<int> nonnegative_, nonnegative_variable_;
    std::vector<int> free_, free_variable_;
};

// Pseudo-inertia J (4x4) of one link's ten standard parameters (XX XY XZ YY YZ ZZ MX MY MZ M) and back.
Eigen::Matrix4d pseudo_inertia(const double* ten);
void from_pseudo_inertia(const Eigen::Matrix4d& J, double* ten);

}  // namespace jacobid::identify
