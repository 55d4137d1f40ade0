#pragma once
// SO(3), the group of 3D rotations, stored as a unit quaternion.
// Tangent vectors are rotation vectors (axis * angle, radians). Templated on
// the scalar so that Ceres' autodiff Jets pass through.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>

namespace dlslam {

template <typename T>
class SO3 {
 public:
  using Scalar = T;
  using Vector3 = Eigen::Matrix<T, 3, 1>;
  using Matrix3 = Eigen::Matrix<T, 3, 3>;
  using Quaternion = Eigen::Quaternion<T>;

  SO3() : q_(Quaternion::Identity()) {}
  // Normalises q; a zero quaternion is a programming error.
  explicit SO3(const Quaternion& q) : q_(q.normalized()) {}
  explicit SO3(const Matrix3& R) : q_(Quaternion(R).normalized()) {}

  static SO3 Identity() { return SO3(); }

  // exp: rotation vector -> rotation. Exact to machine precision near 0.
  static SO3 Exp(const Vector3& omega) {
    using std::cos;
    using std::sin;
    using std::sqrt;
    const T theta_sq = omega.squaredNorm();
    T imag_factor;
    T real_factor;
    if (theta_sq < T(1e-10)) {
      // Taylor series of sin(theta/2)/theta and cos(theta/2).
      imag_factor = T(0.5) - theta_sq / T(48);
      real_factor = T(1) - theta_sq / T(8);
    } else {
      const T theta = sqrt(theta_sq);
      imag_factor = sin(theta / T(2)) / theta;
      real_factor = cos(theta / T(2));
    }
    SO3 r;
    r.q_ = Quaternion(real_factor, imag_factor * omega.x(), imag_factor * omega.y(),
                      imag_factor * omega.z());
    r.q_.normalize();
    return r;
  }

  // log: rotation -> rotation vector with angle in [0, pi].
  Vector3 Log() const {
    using std::abs;
    using std::atan2;
    using std::sqrt;
    const Vector3 v = q_.vec();
    const T n_sq = v.squaredNorm();
    const T w = q_.w();
    T factor;  // 2 * atan(n / w) / n, with the sign of w folded in.
    if (n_sq < T(1e-20)) {
      // Taylor series of 2 atan(n/w) / n around n = 0.
      factor = T(2) / w - T(2) / T(3) * n_sq / (w * w * w);
    } else {
      const T n = sqrt(n_sq);
      // atan2 on (n, |w|) keeps the angle <= pi; q and -q are the same rotation.
      factor = (w < T(0) ? T(-2) : T(2)) * atan2(n, abs(w)) / n;
    }
    return factor * v;
  }

  static Matrix3 Hat(const Vector3& v) {
    Matrix3 m;
    m << T(0), -v.z(), v.y(), v.z(), T(0), -v.x(), -v.y(), v.x(), T(0);
    return m;
  }
  static Vector3 Vee(const Matrix3& m) { return Vector3(m(2, 1), m(0, 2), m(1, 0)); }

  SO3 Inverse() const {
    SO3 r;
    r.q_ = q_.conjugate();
    return r;
  }
  SO3 operator*(const SO3& other) const {
    SO3 r;
    r.q_ = (q_ * other.q_).normalized();
    return r;
  }
  Vector3 operator*(const Vector3& p) const { return q_ * p; }

  Matrix3 matrix() const { return q_.toRotationMatrix(); }
  const Quaternion& quaternion() const { return q_; }
  // Adjoint: Exp(Adj * w) = R * Exp(w) * R^-1.
  Matrix3 Adj() const { return matrix(); }

  template <typename U>
  SO3<U> cast() const {
    return SO3<U>(q_.template cast<U>());
  }

  // Right Jacobian: Exp(w + dw) ~ Exp(w) Exp(Jr(w) dw).
  static Matrix3 RightJacobian(const Vector3& w) { return LeftJacobian(-w); }
  // Left Jacobian: Exp(w + dw) ~ Exp(Jl(w) dw) Exp(w). Also the V matrix of SE3::Exp.
  static Matrix3 LeftJacobian(const Vector3& w) {
    using std::sin;
    using std::sqrt;
    const T theta_sq = w.squaredNorm();
    const Matrix3 W = Hat(w);
    T a;  // (1 - cos theta) / theta^2
    T b;  // (theta - sin theta) / theta^3
    if (theta_sq < T(1e-6)) {
      // Taylor series: the closed forms cancel catastrophically near 0.
      a = T(0.5) - theta_sq / T(24);
      b = T(1) / T(6) - theta_sq / T(120);
    } else {
      const T theta = sqrt(theta_sq);
      const T s = sin(theta / T(2));
      a = T(2) * s * s / theta_sq;
      b = (theta - sin(theta)) / (theta_sq * theta);
    }
    return Matrix3::Identity() + a * W + b * W * W;
  }
  static Matrix3 LeftJacobianInverse(const Vector3& w) {
    using std::cos;
    using std::sin;
    using std::sqrt;
    const T theta_sq = w.squaredNorm();
    const Matrix3 W = Hat(w);
    T c;  // (1 - theta sin(theta) / (2 (1 - cos theta))) / theta^2
    if (theta_sq < T(1e-6)) {
      c = T(1) / T(12) + theta_sq / T(720);
    } else {
      const T theta = sqrt(theta_sq);
      const T half = theta / T(2);
      // theta sin(theta) / (2 (1 - cos theta)) = half * cot(half)
      c = (T(1) - half * cos(half) / sin(half)) / theta_sq;
    }
    return Matrix3::Identity() - T(0.5) * W + c * W * W;
  }
  static Matrix3 RightJacobianInverse(const Vector3& w) { return LeftJacobianInverse(-w); }

 private:
  Quaternion q_;
};

using SO3d = SO3<double>;
using SO3f = SO3<float>;

}  // namespace dlslam
