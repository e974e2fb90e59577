// SPDX-License-Identifier: MIT
#include "identify/physical/physical_parametrization.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

namespace jacobid::identify {
namespace {

constexpr const char* kInertialKinds[10] = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"};

// "ZZ12" -> ("ZZ", "12").
std::pair<std::string, std::string> split_name(const std::string& name) {
    std::size_t digits = name.size();
    while (digits > 0 && std::isdigit(static_cast<unsigned char>(name[digits - 1]))) --digits;
    return {name.substr(0, digits), name.substr(digits)};
}

Eigen::Matrix3d inertia_matrix(const double* ten) {
    Eigen::Matrix3d I;
    I << ten[0], ten[1], ten[2], ten[1], ten[3], ten[4], ten[2], ten[4], ten[5];
    return I;
}

void set_inertia(const Eigen::Matrix3d& I, double* ten) {
    ten[0] = I(0, 0), ten[1] = I(0, 1), ten[2] = I(0, 2), ten[3] = I(1, 1), ten[4] = I(1, 2), ten[5] = I(2, 2);
}

// S = c^T c 1 - c c^T: the inertia of a unit point mass at c about the origin.
Eigen::Matrix3d point_inertia(const Eigen::Vector3d& c) { return c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose(); }

// The symmetric matrix with its eigenvalues raised to max(margin * largest, floor).
template <int N>
Eigen::Matrix<double, N, N> raised(const Eigen::Matrix<double, N, N>& A, double margin, double floor) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(A);
    const double lowest = std::max(margin * std::max(eig.eigenvalues().maxCoeff(), 0.0), floor);
    const Eigen::Matrix<double, N, 1> lambda = eig.eigenvalues().cwiseMax(lowest);
    return eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace

const char* to_string(PhysicalConstraint c) { return c == PhysicalConstraint::Full ? "physical" : "semi-physical"; }

Eigen::Matrix4d pseudo_inertia(const double* ten) {
    const Eigen::Matrix3d I = inertia_matrix(ten);
    Eigen::Matrix4d J;
    J.topLeftCorner<3, 3>() = 0.5 * I.trace() * Eigen::Matrix3d::Identity() - I;
    J.topRightCorner<3, 1>() << ten[6], ten[7], ten[8];
    J.bottomLeftCorner<1, 3>() = J.topRightCorner<3, 1>().transpose();
    J(3, 3) = ten[9];
    return J;
}

void from_pseudo_inertia(const Eigen::Matrix4d& J, double* ten) {
    const Eigen::Matrix3d sigma = J.topLeftCorner<3, 3>();
    set_inertia(sigma.trace() * Eigen::Matrix3d::Identity() - sigma, ten);  // tr(Sigma) = tr(I) / 2
    ten[6] = J(0, 3), ten[7] = J(1, 3), ten[8] = J(2, 3), ten[9] = J(3, 3);
}

PhysicalParametrization::PhysicalParametrization(const std::vector<std::string>& names, PhysicalConstraint constraint)
    : constraint_(constraint), standard_count_(static_cast<int>(names.size())) {
    for (int c = 0; c < standard_count_;) {
        const auto [kind, index] = split_name(names[static_cast<std::size_t>(c)]);
        if (kind == "XX") {
            for (int k = 0; k < 10; ++k) {
                if (c + k >= standard_count_ || names[static_cast<std::size_t>(c + k)] != kInertialKinds[k] + index) {
                    throw std::invalid_argument("standard parameters of link " + index + " are not the ten XX .. M in order");
                }
            }
            links_.push_back({c, variable_count_});
            variable_count_ += 10;
            c += 10;
            continue;
        }
        if (kind == "IA" || kind == "FV" || kind == "FC" || kind == "FD") {
            nonnegative_.push_back(c);
            nonnegative_variable_.push_back(variable_count_++);
        } else {
            free_.push_back(c);
            free_variable_.push_back(variable_count_++);
        }
        ++c;
    }
}

Eigen::VectorXd PhysicalParametrization::standard(const Eigen::VectorXd& v) const {
    Eigen::VectorXd s = Eigen::VectorXd::Zero(standard_count_);
    for (const Link& link : links_) {
        const double* x = v.data() + link.first_variable;
        double* ten = s.data() + link.first_column;
        if (constraint_ == PhysicalConstraint::Full) {
            Eigen::Matrix4d U = Eigen::Matrix4d::Zero();
            for (int i = 0; i < 4; ++i) U(i, i) = std::exp(x[i]);
            U(0, 1) = x[4], U(0, 2) = x[5], U(0, 3) = x[6], U(1, 2) = x[7], U(1, 3) = x[8], U(2, 3) = x[9];
            from_pseudo_inertia(U * U.transpose(), ten);
        } else {
            const double m = std::exp(x[0]);
            const Eigen::Vector3d c(x[1], x[2], x[3]);
            Eigen::Matrix3d L = Eigen::Matrix3d::Zero();
            for (int i = 0; i < 3; ++i) L(i, i) = std::exp(x[4 + i]);
            L(1, 0) = x[7], L(2, 0) = x[8], L(2, 1) = x[9];
            set_inertia(L * L.transpose() + m * point_inertia(c), ten);
            ten[6] = m * c[0], ten[7] = m * c[1], ten[8] = m * c[2], ten[9] = m;
        }
    }
    for (std::size_t k = 0; k < nonnegative_.size(); ++k) s[nonnegative_[k]] = std::exp(v[nonnegative_variable_[k]]);
    for (std::size_t k = 0; k < free_.size(); ++k) s[free_[k]] = v[free_variable_[k]];
    return s;
}

Eigen::VectorXd PhysicalParametrization::variables(const Eigen::VectorXd& s, double margin, double floor) const {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(variable_count_);
    for (const Link& link : links_) {
        const double* ten = s.data() + link.first_column;
        double* x = v.data() + link.first_variable;
        if (constraint_ == PhysicalConstraint::Full) {
            // J = U U^T with U upper triangular: the Cholesky factor of J with rows and columns reversed.
            const Eigen::Matrix4d J = raised<4>(pseudo_inertia(ten), margin, floor);
            const Eigen::Matrix4d reversed = J.reverse();
            const Eigen::Matrix4d L = Eigen::LLT<Eigen::Matrix4d>(reversed).matrixL();
            const Eigen::Matrix4d U = L.reverse();
            for (int i = 0; i < 4; ++i) x[i] = std::log(U(i, i));
            x[4] = U(0, 1), x[5] = U(0, 2), x[6] = U(0, 3), x[7] = U(1, 2), x[8] = U(1, 3), x[9] = U(2, 3);
        } else {
            // A mass at or below the floor says nothing about where the centre of mass is (h / m would put it
            // arbitrarily far away): the start keeps the floor mass at the origin.
            const bool massive = ten[9] > floor;
            const double m = massive ? ten[9] : floor;
            const Eigen::Vector3d c = massive ? Eigen::Vector3d(Eigen::Vector3d(ten[6], ten[7], ten[8]) / m) : Eigen::Vector3d::Zero();
            const Eigen::Matrix3d Ic = raised<3>(Eigen::Matrix3d(inertia_matrix(ten) - m * point_inertia(c)), margin, floor);
            const Eigen::Matrix3d L = Eigen::LLT<Eigen::Matrix3d>(Ic).matrixL();
            x[0] = std::log(m), x[1] = c[0], x[2] = c[1], x[3] = c[2];
            for (int i = 0; i < 3; ++i) x[4 + i] = std::log(L(i, i));
            x[7] = L(1, 0), x[8] = L(2, 0), x[9] = L(2, 1);
        }
    }
    for (std::size_t k = 0; k < nonnegative_.size(); ++k) v[nonnegative_variable_[k]] = std::log(std::max(s[nonnegative_[k]], floor));
    for (std::size_t k = 0; k < free_.size(); ++k) v[free_variable_[k]] = s[free_[k]];
    return v;
}

std::vector<LmiBlock> PhysicalParametrization::constraint_blocks() const {
    std::vector<LmiBlock> blocks;
    for (const Link& link : links_) {
        LmiBlock b;
        b.size = constraint_ == PhysicalConstraint::Full ? 4 : 6;
        for (int k = 0; k < 10; ++k) {
            double unit[10] = {};
            unit[k] = 1.0;
            Eigen::MatrixXd F;
            if (constraint_ == PhysicalConstraint::Full) {
                F = pseudo_inertia(unit);
            } else {
                F = Eigen::MatrixXd::Zero(6, 6);
                F.topLeftCorner<3, 3>() = inertia_matrix(unit);
                Eigen::Matrix3d S;  // S(h): S(h) v = h x v
                S << 0.0, -unit[8], unit[7], unit[8], 0.0, -unit[6], -unit[7], unit[6], 0.0;
                F.bottomLeftCorner<3, 3>() = S;
                F.topRightCorner<3, 3>() = S.transpose();
                F.bottomRightCorner<3, 3>() = unit[9] * Eigen::Matrix3d::Identity();
            }
            if (F.cwiseAbs().maxCoeff() > 0.0) b.terms.push_back({link.first_column + k, F});
        }
        blocks.push_back(std::move(b));
    }
    for (const int c : nonnegative_) blocks.push_back({1, {{c, Eigen::MatrixXd::Ones(1, 1)}}});
    return blocks;
}

double PhysicalParametrization::link_relative_min_eigenvalue(const Eigen::VectorXd& s, int link) const {
    const double* ten = s.data() + links_[static_cast<std::size_t>(link)].first_column;
    if (constraint_ == PhysicalConstraint::Full) {
        const Eigen::Vector4d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(pseudo_inertia(ten), Eigen::EigenvaluesOnly).eigenvalues();
        return lambda.maxCoeff() > 0.0 ? lambda.minCoeff() / lambda.maxCoeff() : -1.0;
    }
    if (!(ten[9] > 0.0)) return -1.0;
    const Eigen::Vector3d c = Eigen::Vector3d(ten[6], ten[7], ten[8]) / ten[9];
    const Eigen::Matrix3d Ic = inertia_matrix(ten) - ten[9] * point_inertia(c);
    const Eigen::Vector3d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Ic, Eigen::EigenvaluesOnly).eigenvalues();
    return lambda.maxCoeff() > 0.0 ? lambda.minCoeff() / lambda.maxCoeff() : -1.0;
}

}  // namespace jacobid::identify
