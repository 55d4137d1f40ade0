#pragma once
// SE(3), rigid-body transforms. Named by the frames they map between:
// `cam_from_world * p_world = p_cam` (see docs/conventions.md).
// Tangent vectors are (rho, omega): translation part first, as in Sophus.

#include <Eigen/Core>

#include "dlslam/geometry/so3.h"

namespace dlslam {

template <typename T>
class SE3 {
 public:
  using Scalar = T;
  using Vector3 = Eigen::Matrix<T, 3, 1>;
  using Vector6 = Eigen::Matrix<T, 6, 1>;
  using Matrix3 = Eigen::Matrix<T, 3, 3>;
  using Matrix4 = Eigen::Matrix<T, 4, 4>;
  using Matrix34 = Eigen::Matrix<T, 3, 4>;
  using Matrix6 = Eigen::Matrix<T, 6, 6>;

  SE3() : translation_(Vector3::Zero()) {}
  SE3(const SO3<T>& rotation, const Vector3& translation)
      : rotation_(rotation), translation_(translation) {}
  SE3(const Eigen::Quaternion<T>& q, const Vector3& translation)
      : rotation_(q), translation_(translation) {}
  // From a 4x4 (or 3x4) matrix whose rotation block is orthonormal.
  explicit SE3(const Matrix4& m) : rotation_(Matrix3(m.template topLeftCorner<3, 3>())),
                                   translation_(m.template topRightCorner<3, 1>()) {}

  static SE3 Identity() { return SE3(); }

  static SE3 Exp(const Vector6& xi) {
    const Vector3 rho = xi.template head<3>();
    const Vector3 omega = xi.template tail<3>();
    return SE3(SO3<T>::Exp(omega), SO3<T>::LeftJacobian(omega) * rho);
  }

  Vector6 Log() const {
    const Vector3 omega = rotation_.Log();
    Vector6 xi;
    xi.template head<3>() = SO3<T>::LeftJacobianInverse(omega) * translation_;
    xi.template tail<3>() = omega;
    return xi;
  }

  // 4x4 matrix of a tangent vector.
  static Matrix4 Hat(const Vector6& xi) {
    Matrix4 m = Matrix4::Zero();
    m.template topLeftCorner<3, 3>() = SO3<T>::Hat(xi.template tail<3>());
    m.template topRightCorner<3, 1>() = xi.template head<3>();
    return m;
  }

  SE3 Inverse() const {
    const SO3<T> r_inv = rotation_.Inverse();
    return SE3(r_inv, -(r_inv * translation_));
  }
  SE3 operator*(const SE3& other) const {
    return SE3(rotation_ * other.rotation_, rotation_ * other.translation_ + translation_);
  }
  Vector3 operator*(const Vector3& p) const { return rotation_ * p + translation_; }

  // Adjoint: Exp(Adj * xi) = T * Exp(xi) * T^-1.
  Matrix6 Adj() const {
    const Matrix3 R = rotation_.matrix();
    Matrix6 adj;
    adj << R, SO3<T>::Hat(translation_) * R, Matrix3::Zero(), R;
    return adj;
  }

  Matrix4 matrix() const {
    Matrix4 m = Matrix4::Identity();
    m.template topLeftCorner<3, 3>() = rotation_.matrix();
    m.template topRightCorner<3, 1>() = translation_;
    return m;
  }
  Matrix34 matrix3x4() const { return matrix().template topRows<3>(); }

  const SO3<T>& so3() const { return rotation_; }
  SO3<T>& so3() { return rotation_; }
  const Vector3& translation() const { return translation_; }
  Vector3& translation() { return translation_; }
  Matrix3 rotationMatrix() const { return rotation_.matrix(); }
  const Eigen::Quaternion<T>& unit_quaternion() const { return rotation_.quaternion(); }

  template <typename U>
  SE3<U> cast() const {
    return SE3<U>(rotation_.template cast<U>(), translation_.template cast<U>());
  }

 private:
  SO3<T> rotation_;
  Vector3 translation_;
};

using SE3d = SE3<double>;
using SE3f = SE3<float>;

}  // namespace dlslam
