// Central finite differences, for derivative checks in tests and in debug runs.
#pragma once

#include <Eigen/Core>
#include <functional>

namespace superdex {

using ScalarFunction = std::function<double(const Eigen::VectorXd&)>;
using VectorFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

/// ∂f/∂x by central differences with step h: (f(x + h e_i) - f(x - h e_i)) / 2h.
Eigen::VectorXd FiniteDifferenceGradient(const ScalarFunction& f, const Eigen::VectorXd& x,
                                         double h);

/// ∂F/∂x (rows: outputs) by central differences with step h.
Eigen::MatrixXd FiniteDifferenceJacobian(const VectorFunction& F, const Eigen::VectorXd& x,
                                         double h);

}  // namespace superdex
