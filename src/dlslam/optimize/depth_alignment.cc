#include "dlslam/optimize/depth_alignment.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "dlslam/util/check.h"

namespace dlslam {

void DepthAlignmentOptions::Check() const {
  DLSLAM_CHECK(sample_step >= 1 && sample_step <= 64, "DepthAlignmentOptions::sample_step {} outside [1, 64]",
               sample_step);
  DLSLAM_CHECK(iterations >= 1 && iterations <= 100, "DepthAlignmentOptions::iterations {} outside [1, 100]",
               iterations);
  DLSLAM_CHECK(noise_m > 0 && noise_m < 1, "DepthAlignmentOptions::noise_m {} outside (0, 1)", noise_m);
  DLSLAM_CHECK(noise_per_m2 >= 0 && noise_per_m2 < 1, "DepthAlignmentOptions::noise_per_m2 {} outside [0, 1)",
               noise_per_m2);
  DLSLAM_CHECK(tukey_sigmas >= 1 && tukey_sigmas <= 20, "DepthAlignmentOptions::tukey_sigmas {} outside [1, 20]",
               tukey_sigmas);
  DLSLAM_CHECK(max_distance_m > 0 && max_distance_m <= 2, "DepthAlignmentOptions::max_distance_m {} outside (0, 2]",
               max_distance_m);
  DLSLAM_CHECK(min_depth_m > 0 && min_depth_m < max_depth_m,
               "DepthAlignmentOptions: need 0 < min_depth_m {} < max_depth_m {}", min_depth_m, max_depth_m);
  DLSLAM_CHECK(min_step > 0, "DepthAlignmentOptions::min_step {} must be > 0", min_step);
  DLSLAM_CHECK(min_inliers >= 6, "DepthAlignmentOptions::min_inliers {} must be >= 6", min_inliers);
}

DepthAligner::DepthAligner(const CameraIntrinsics& camera, const DepthAlignmentOptions& options)
    : camera_(camera), options_(options) {
  options_.Check();
  camera_.Check();
  BuildRays();
}

void DepthAligner::BuildRays() {
  rays_ = PixelRays(camera_);
  const int w = camera_.width / 2, h = camera_.height / 2;
  half_rays_.assign(static_cast<std::size_t>(w * h), Eigen::Vector2f::Zero());
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      Eigen::Vector2f sum = Eigen::Vector2f::Zero();
      for (int dv = 0; dv < 2; ++dv) {
        for (int du = 0; du < 2; ++du)
          sum += rays_[static_cast<std::size_t>((2 * v + dv) * camera_.width + 2 * u + du)];
      }
      half_rays_[static_cast<std::size_t>(v * w + u)] = sum / 4.0f;
    }
  }
}

void DepthAligner::CheckDepth(const cv::Mat& depth, const char* what) const {
  DLSLAM_CHECK(depth.type() == CV_32FC1 && depth.cols == camera_.width && depth.rows == camera_.height,
               "{} depth must be float metres {}x{}, got type {} {}x{}", what, camera_.width, camera_.height,
               depth.type(), depth.cols, depth.rows);
}

bool DepthAligner::PointAt(const cv::Mat& depth, int u, int v, Eigen::Vector3f* point) const {
  const float z = depth.ptr<float>(v)[u];
  // NaN fails both comparisons.
  if (!(z >= options_.min_depth_m && z <= options_.max_depth_m)) return false;
  const Eigen::Vector2f& ray = rays_[static_cast<std::size_t>(v * camera_.width + u)];
  *point = Eigen::Vector3f(ray.x() * z, ray.y() * z, z);
  return true;
}

bool DepthAligner::HalfPointAt(const cv::Mat& half, int u, int v, Eigen::Vector3f* point) const {
  const float z = half.ptr<float>(v)[u];
  if (!(z > 0)) return false;
  const Eigen::Vector2f& ray = half_rays_[static_cast<std::size_t>(v * half.cols + u)];
  *point = Eigen::Vector3f(ray.x() * z, ray.y() * z, z);
  return true;
}

bool DepthAligner::Correspondence(const cv::Mat& reference_half, const Eigen::Vector3f& p_ref, Eigen::Vector3f* q,
                                  Eigen::Vector3f* normal) const {
  if (!(p_ref.z() > static_cast<float>(options_.min_depth_m))) return false;
  const Eigen::Vector2d xn(p_ref.x() / p_ref.z(), p_ref.y() / p_ref.z());
  const Eigen::Vector2d xd = camera_.HasDistortion() ? camera_.Distort(xn) : xn;
  // Block (u, v) covers full-resolution pixels 2u, 2u + 1: centre 2u + 0.5.
  const int u = static_cast<int>(std::lround((camera_.fx * xd.x() + camera_.cx - 0.5) / 2));
  const int v = static_cast<int>(std::lround((camera_.fy * xd.y() + camera_.cy - 0.5) / 2));
  constexpr int kNormalReach = 2;  // [blocks]: neighbours for the normal (4 px)
  if (u < kNormalReach || v < kNormalReach || u >= reference_half.cols - kNormalReach ||
      v >= reference_half.rows - kNormalReach) {
    return false;
  }
  Eigen::Vector3f left, right, up, down;
  if (!HalfPointAt(reference_half, u, v, q) || !HalfPointAt(reference_half, u - kNormalReach, v, &left) ||
      !HalfPointAt(reference_half, u + kNormalReach, v, &right) ||
      !HalfPointAt(reference_half, u, v - kNormalReach, &up) ||
      !HalfPointAt(reference_half, u, v + kNormalReach, &down)) {
    return false;
  }
  // Across a depth edge the neighbours belong to different surfaces: no normal.
  const float jump = 0.05f * q->z();
  if (std::abs(left.z() - right.z()) > 2 * jump || std::abs(up.z() - down.z()) > 2 * jump) return false;
  Eigen::Vector3f n = (right - left).cross(down - up);
  const float length = n.norm();
  if (!(length > 0)) return false;
  n /= length;
  if (n.dot(*q) > 0) n = -n;  // towards the camera
  *normal = n;
  return true;
}

std::vector<DepthAligner::Sample> DepthAligner::Samples(const cv::Mat& current_depth) const {
  std::vector<Sample> samples;
  const int step = options_.sample_step;
  samples.reserve(static_cast<std::size_t>((camera_.width / step + 1) * (camera_.height / step + 1)));
  for (int v = step / 2; v < camera_.height; v += step) {
    for (int u = step / 2; u < camera_.width; u += step) {
      Eigen::Vector3f p;
      if (PointAt(current_depth, u, v, &p)) samples.push_back({p});
    }
  }
  return samples;
}

void DepthAligner::Accumulate(const cv::Mat& reference_depth, const std::vector<Sample>& samples,
                              const SE3d& reference_from_current, Eigen::Matrix<double, 6, 6>* h,
                              Eigen::Matrix<double, 6, 1>* g, int* inliers, double kernel_scale) const {
  const Eigen::Matrix3f r = reference_from_current.rotationMatrix().cast<float>();
  const Eigen::Vector3f t = reference_from_current.translation().cast<float>();
  Eigen::Matrix<double, 6, 6> h_sum = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> g_sum = Eigen::Matrix<double, 6, 1>::Zero();
  int count = 0;
  const double tukey = options_.tukey_sigmas * kernel_scale;
  for (const Sample& s : samples) {
    const Eigen::Vector3f p = r * s.point + t;
    Eigen::Vector3f q, n;
    if (!Correspondence(reference_depth, p, &q, &n)) continue;
    if ((p - q).squaredNorm() > options_.max_distance_m * options_.max_distance_m) continue;
    const double residual = n.dot(p - q);
    const double sigma = options_.noise_m + options_.noise_per_m2 * static_cast<double>(q.z()) * q.z();
    const double e = residual / sigma;
    if (std::abs(e) < 3.0) ++count;
    if (h == nullptr || std::abs(e) >= tukey) continue;
    const double a = 1.0 - (e / tukey) * (e / tukey);
    const double w = a * a / (sigma * sigma);
    Eigen::Matrix<double, 6, 1> j;
    j.head<3>() = n.cast<double>();
    j.tail<3>() = p.cross(n).cast<double>();
    h_sum.noalias() += w * j * j.transpose();
    g_sum.noalias() += w * residual * j;
  }
  if (h != nullptr) *h = h_sum;
  if (g != nullptr) *g = g_sum;
  *inliers = count;
}

PreparedDepth DepthAligner::Prepare(const cv::Mat& depth) const {
  PreparedDepth out;
  Prepare(depth, &out);
  return out;
}

void DepthAligner::Prepare(const cv::Mat& depth, PreparedDepth* out) const {
  CheckDepth(depth, "reference");
  const int w = camera_.width / 2, h = camera_.height / 2;
  out->blocks.create(h, w, CV_32FC1);
  out->half.create(h, w, CV_32FC1);
  const float lo = static_cast<float>(options_.min_depth_m), hi = static_cast<float>(options_.max_depth_m);
  for (int v = 0; v < h; ++v) {
    const float* r0 = depth.ptr<float>(2 * v);
    const float* r1 = depth.ptr<float>(2 * v + 1);
    float* b = out->blocks.ptr<float>(v);
    for (int u = 0; u < w; ++u) {
      const float z[4] = {r0[2 * u], r0[2 * u + 1], r1[2 * u], r1[2 * u + 1]};
      float sum = 0, z_min = hi, z_max = lo;
      int n = 0;
      for (float d : z) {
        if (!(d >= lo && d <= hi)) continue;  // NaN too
        sum += d;
        z_min = std::min(z_min, d);
        z_max = std::max(z_max, d);
        ++n;
      }
      // A block across a depth edge has no single surface: none.
      b[u] = n >= 3 && z_max - z_min < 0.02f + 0.02f * z_min ? sum / static_cast<float>(n) : 0.0f;
    }
  }
  for (int v = 0; v < h; ++v) {
    float* o = out->half.ptr<float>(v);
    const float* centre_row = out->blocks.ptr<float>(v);
    for (int u = 0; u < w; ++u) {
      const float c = centre_row[u];
      o[u] = c;
      if (c <= 0 || u == 0 || v == 0 || u == w - 1 || v == h - 1) continue;
      float sum = 0;
      int n = 0;
      for (int dv = -1; dv <= 1; ++dv) {
        const float* row = out->blocks.ptr<float>(v + dv);
        for (int du = -1; du <= 1; ++du) {
          const float d = row[u + du];
          if (d > 0 && std::abs(d - c) < 0.03f * c) {
            sum += d;
            ++n;
          }
        }
      }
      o[u] = sum / static_cast<float>(n);  // n >= 1: the centre itself
    }
  }
}

DepthAlignment DepthAligner::Score(const cv::Mat& reference_depth, const cv::Mat& current_depth,
                                   const SE3d& current_from_reference) const {
  return Score(Prepare(reference_depth), current_depth, current_from_reference);
}

DepthAlignment DepthAligner::Align(const cv::Mat& reference_depth, const cv::Mat& current_depth,
                                   const SE3d& guess) const {
  return Align(Prepare(reference_depth), current_depth, guess);
}

DepthAlignment DepthAligner::Score(const PreparedDepth& reference, const cv::Mat& current_depth,
                                   const SE3d& current_from_reference) const {
  const cv::Mat& reference_depth = reference.half;
  CheckDepth(current_depth, "current");
  DepthAlignment out;
  out.current_from_reference = current_from_reference;
  const std::vector<Sample> samples = Samples(current_depth);
  out.samples = static_cast<int>(samples.size());
  Accumulate(reference_depth, samples, current_from_reference.Inverse(), nullptr, nullptr, &out.inliers, 1.0);
  out.inlier_fraction = out.samples > 0 ? static_cast<double>(out.inliers) / out.samples : 0.0;
  return out;
}

DepthAlignment DepthAligner::Align(const PreparedDepth& reference, const cv::Mat& current_depth,
                                   const SE3d& guess) const {
  const cv::Mat& reference_depth = reference.half;
  DLSLAM_CHECK(reference_depth.type() == CV_32FC1 && reference_depth.cols == camera_.width / 2 &&
                   reference_depth.rows == camera_.height / 2,
               "the reference was not prepared for this camera");
  CheckDepth(current_depth, "current");
  DepthAlignment out;
  const std::vector<Sample> samples = Samples(current_depth);
  out.samples = static_cast<int>(samples.size());
  SE3d reference_from_current = guess.Inverse();
  bool well_conditioned = false;
  for (int it = 0; it < options_.iterations; ++it) {
    Eigen::Matrix<double, 6, 6> h;
    Eigen::Matrix<double, 6, 1> g;
    int inliers = 0;
    // Graduated: a wide kernel first so that a rough guess finds the static
    // surfaces, then the narrow one that rejects a mover near them.
    const double kernel_scale = std::max(1.0, 3.0 - it);
    Accumulate(reference_depth, samples, reference_from_current, &h, &g, &inliers, kernel_scale);
    out.iterations = it + 1;
    // A view of one plane (or two) leaves directions unconstrained: then the
    // fit says nothing about them and must not be trusted.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(h, Eigen::EigenvaluesOnly);
    const double largest = eigen.eigenvalues()(5);
    well_conditioned = largest > 0 && eigen.eigenvalues()(0) > 1e-6 * largest;
    if (!well_conditioned) break;
    const Eigen::Matrix<double, 6, 1> delta = h.ldlt().solve(-g);
    if (!delta.allFinite()) {
      well_conditioned = false;
      break;
    }
    reference_from_current = SE3d::Exp(delta) * reference_from_current;
    if (kernel_scale == 1.0 && delta.norm() < options_.min_step) break;
  }
  Accumulate(reference_depth, samples, reference_from_current, nullptr, nullptr, &out.inliers, 1.0);
  out.current_from_reference = reference_from_current.Inverse();
  out.inlier_fraction = out.samples > 0 ? static_cast<double>(out.inliers) / out.samples : 0.0;
  out.converged = well_conditioned && out.inliers >= options_.min_inliers;
  return out;
}

}  // namespace dlslam
