#pragma once
// Central-difference Jacobians for checking analytic derivatives in tests.

#include <Eigen/Core>

namespace dlslam::testing {

// J(i, j) = d f_i / d x_j at x0, by central differences with step h.
template <int Rows, int Cols, typename F>
Eigen::Matrix<double, Rows, Cols> NumericJacobian(const F& f, const Eigen::Matrix<double, Cols, 1>& x0,
                                                  double h = 1e-6) {
  Eigen::Matrix<double, Rows, Cols> J;
  for (int j = 0; j < Cols; ++j) {
    Eigen::Matrix<double, Cols, 1> dx = Eigen::Matrix<double, Cols, 1>::Zero();
    dx[j] = h;
    J.col(j) = (f(x0 + dx) - f(x0 - dx)) / (2 * h);
  }
  return J;
}

}  // namespace dlslam::testing
