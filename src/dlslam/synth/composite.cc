#include "dlslam/synth/composite.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "dlslam/synth/actors.h"
#include "dlslam/synth/renderer.h"
#include "dlslam/util/check.h"

namespace dlslam::synth {

void CompositeOptions::Check() const {
  DLSLAM_CHECK(people >= 1 && people <= 20, "CompositeOptions::people {} outside [1, 20]", people);
  DLSLAM_CHECK(min_distance_m >= 0.3 && min_distance_m <= max_distance_m && max_distance_m <= 20,
               "CompositeOptions: need 0.3 <= min_distance_m {} <= max_distance_m {} <= 20", min_distance_m,
               max_distance_m);
  DLSLAM_CHECK(speed_mps >= 0 && speed_mps <= 10, "CompositeOptions::speed_mps {} outside [0, 10]", speed_mps);
  DLSLAM_CHECK(path_length_m > 0 && path_length_m <= 100, "CompositeOptions::path_length_m {} outside (0, 100]",
               path_length_m);
  DLSLAM_CHECK(height_m >= 0.3 && height_m <= 3 && height_spread_m >= 0 && height_spread_m < height_m / 2,
               "CompositeOptions: height_m {} outside [0.3, 3] or height_spread_m {} outside [0, height / 2)",
               height_m, height_spread_m);
  DLSLAM_CHECK(body_depth_m >= 0 && body_depth_m <= 1, "CompositeOptions::body_depth_m {} outside [0, 1]",
               body_depth_m);
  DLSLAM_CHECK(noise_per_m2 >= 0 && noise_per_m2 <= 0.1, "CompositeOptions::noise_per_m2 {} outside [0, 0.1]",
               noise_per_m2);
  DLSLAM_CHECK(outline_hole_px >= 0 && outline_hole_px <= 20, "CompositeOptions::outline_hole_px {} outside [0, 20]",
               outline_hole_px);
}

PeopleCompositor::PeopleCompositor(const CameraIntrinsics& camera, std::vector<Cutout> cutouts,
                                   const CompositeOptions& options, const Trajectory& camera_path)
    : camera_(camera), options_(options) {
  camera_.Check();
  options_.Check();
  DLSLAM_CHECK(!camera_path.empty(), "no camera poses to lay the walkers out along");
  first_t_ = camera_path.front().timestamp;
  DLSLAM_CHECK(!cutouts.empty(), "no person cut-outs to walk through the scene");
  for (const Cutout& c : cutouts) {
    DLSLAM_CHECK(c.bgr.type() == CV_8UC3 && c.mask.type() == CV_8UC1 && c.bgr.size() == c.mask.size(),
                 "cut-out '{}': need a BGR photo and an 8-bit mask of the same size", c.name);
    const cv::Rect box = cv::boundingRect(c.mask);
    DLSLAM_CHECK(box.width >= 8 && box.height >= 16, "cut-out '{}': its mask holds no person ({}x{} px)", c.name,
                 box.width, box.height);
    PreparedCutout p;
    p.bgr = c.bgr(box).clone();
    p.mask = c.mask(box) > 0;
    // Thickness of the body: distance to the outline, saturating at a sixth
    // of the person's width (so the torso is full, arms and edges thin).
    cv::Mat distance;
    cv::distanceTransform(p.mask, distance, cv::DIST_L2, 3);
    const double full = std::max(2.0, box.width / 6.0);
    distance.convertTo(p.thickness, CV_32F, 1.0 / full);
    cv::min(p.thickness, 1.0, p.thickness);
    cutouts_.push_back(std::move(p));
  }

  rays_ = PixelRays(camera_);

  // The walkers' lines, horizontal, each in front of the camera of a random frame.
  up_ = -camera_path.front().world_from_cam().rotationMatrix().col(1);
  std::mt19937 rng(options_.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < options_.people; ++i) {
    // The first walker meets the first camera; the others a random one.
    const std::size_t frame = i == 0 ? 0 : rng() % camera_path.size();
    const SE3d world_from_cam = camera_path[frame].world_from_cam();
    const Eigen::Vector3d centre = world_from_cam.translation();
    const Eigen::Vector3d axis = world_from_cam.rotationMatrix().col(2);
    Eigen::Vector3d forward = axis - axis.dot(up_) * up_;
    if (forward.norm() < 1e-3) forward = up_.unitOrthogonal();  // looking straight up or down
    forward.normalize();
    const Eigen::Vector3d right = forward.cross(up_).normalized();  // the camera's +x, horizontal
    Walker w;
    w.cutout = i % static_cast<int>(cutouts_.size());  // the caller's cut-outs in turn
    const PreparedCutout& c = cutouts_[static_cast<std::size_t>(w.cutout)];
    w.height = options_.height_m + options_.height_spread_m * (2 * unit(rng) - 1);
    w.width = w.height * c.mask.cols / static_cast<double>(c.mask.rows);
    const double distance = options_.min_distance_m + (options_.max_distance_m - options_.min_distance_m) * unit(rng);
    // Mostly across the view, up to 35 deg off it.
    const double heading = (2 * unit(rng) - 1) * 35.0 * 3.14159265358979323846 / 180.0;
    w.direction = (std::cos(heading) * right + std::sin(heading) * forward).normalized();
    // The head a little above a hand-held camera.
    w.anchor = centre + distance * forward + (0.2 - w.height / 2) * up_;
    w.phase_m = unit(rng) * 2 * options_.path_length_m;
    walkers_.push_back(w);
  }
}

Eigen::Vector3d PeopleCompositor::PositionAt(const Walker& w, double t) const {
  // Back and forth: a triangle wave over [-L/2, L/2].
  const double l = options_.path_length_m;
  const double s = std::fmod(w.phase_m + options_.speed_mps * std::max(0.0, t - first_t_), 2 * l);
  const double along = (s < l ? s : 2 * l - s) - l / 2;
  return w.anchor + along * w.direction;
}

CompositedFrame PeopleCompositor::Composite(double t, const SE3d& world_from_cam, const cv::Mat& colour,
                                            const cv::Mat& depth) const {
  DLSLAM_CHECK(colour.type() == CV_8UC3 && colour.cols == camera_.width && colour.rows == camera_.height,
               "the colour frame must be BGR {}x{}", camera_.width, camera_.height);
  DLSLAM_CHECK(depth.type() == CV_32FC1 && depth.size() == colour.size(), "the depth frame must be float metres {}x{}",
               camera_.width, camera_.height);
  CompositedFrame out;
  out.colour = colour.clone();
  out.depth = depth.clone();
  out.mask = cv::Mat::zeros(colour.size(), CV_8UC1);
  const SE3d cam_from_world = world_from_cam.Inverse();
  const Eigen::Vector3d camera_centre = world_from_cam.translation();
  std::mt19937 rng(options_.seed * 7919u + static_cast<unsigned>(std::llround(t * 1000.0)));
  std::normal_distribution<float> noise(0.0f, 1.0f);
  const std::uint8_t label = MaskValue(kClassPerson, true);

  // Far to near, so that nearer people cover farther ones.
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t i = 0; i < walkers_.size(); ++i) {
    order.emplace_back(-(PositionAt(walkers_[i], t) - camera_centre).norm(), i);
  }
  std::sort(order.begin(), order.end());
  for (const auto& entry : order) {
    const Walker& w = walkers_[entry.second];
    const PreparedCutout& c = cutouts_[static_cast<std::size_t>(w.cutout)];
    const Eigen::Vector3d position = PositionAt(w, t);
    // Turned towards the camera about the vertical.
    Eigen::Vector3d normal = camera_centre - position;
    normal -= normal.dot(up_) * up_;
    if (normal.norm() < 1e-6) continue;
    normal.normalize();
    const Eigen::Vector3d across = up_.cross(normal).normalized();
    // The billboard in the camera frame.
    const Eigen::Vector3d p_c = cam_from_world * position;
    const Eigen::Matrix3d r = cam_from_world.rotationMatrix();
    const Eigen::Vector3d n_c = r * normal, across_c = r * across, up_c = r * up_;
    if (p_c.z() < 0.2) continue;
    // Its image bounding box from the four corners (behind the camera: skip).
    double u_min = 1e9, u_max = -1e9, v_min = 1e9, v_max = -1e9;
    bool visible = true;
    for (int sx : {-1, 1}) {
      for (int sy : {-1, 1}) {
        const Eigen::Vector3d corner = p_c + sx * w.width / 2 * across_c + sy * w.height / 2 * up_c;
        if (corner.z() < 0.05) visible = false;
        const Eigen::Vector2d uv = camera_.Project(corner);
        u_min = std::min(u_min, uv.x());
        u_max = std::max(u_max, uv.x());
        v_min = std::min(v_min, uv.y());
        v_max = std::max(v_max, uv.y());
      }
    }
    if (!visible) continue;
    // Distortion moves the outline a little: a margin.
    const int u0 = std::max(0, static_cast<int>(std::floor(u_min)) - 8);
    const int u1 = std::min(camera_.width - 1, static_cast<int>(std::ceil(u_max)) + 8);
    const int v0 = std::max(0, static_cast<int>(std::floor(v_min)) - 8);
    const int v1 = std::min(camera_.height - 1, static_cast<int>(std::ceil(v_max)) + 8);
    const double plane = p_c.dot(n_c);
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) {
        const Eigen::Vector2f& ray2 = rays_[static_cast<std::size_t>(v * camera_.width + u)];
        const Eigen::Vector3d ray(ray2.x(), ray2.y(), 1.0);
        const double denominator = ray.dot(n_c);
        if (std::abs(denominator) < 1e-9) continue;
        const Eigen::Vector3d x = (plane / denominator) * ray;
        if (x.z() <= 0) continue;
        const double a = (x - p_c).dot(across_c) / w.width + 0.5;  // 0 = left edge
        const double b = 0.5 - (x - p_c).dot(up_c) / w.height;    // 0 = top
        if (a < 0 || a >= 1 || b < 0 || b >= 1) continue;
        const int cu = std::min(c.mask.cols - 1, static_cast<int>(a * c.mask.cols));
        const int cv_row = std::min(c.mask.rows - 1, static_cast<int>(b * c.mask.rows));
        if (c.mask.at<uchar>(cv_row, cu) == 0) continue;
        // The body bulges towards the camera, most at the torso.
        const double thickness = c.thickness.at<float>(cv_row, cu);
        const double bulge = options_.body_depth_m / 2 * std::sqrt(thickness * (2 - thickness));
        const float z = static_cast<float>(x.z() - bulge * std::abs(n_c.z()));
        const float real = out.depth.at<float>(v, u);
        // A real surface in front (a table edge, a chair) hides the person.
        if (real > 0 && real < z - 0.02f) continue;
        out.colour.at<cv::Vec3b>(v, u) = c.bgr.at<cv::Vec3b>(cv_row, cu);
        const float sigma = static_cast<float>(options_.noise_per_m2) * z * z;
        out.depth.at<float>(v, u) = z + sigma * noise(rng);
        out.mask.at<uchar>(v, u) = label;
      }
    }
  }
  // Structured-light sensors see no depth along a depth edge: a band of
  // holes inside the people's outline.
  if (options_.outline_hole_px > 0) {
    cv::Mat inner;
    const int k = 2 * options_.outline_hole_px + 1;
    cv::erode(out.mask, inner, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
    const cv::Mat band = (out.mask != 0) & (inner == 0);
    out.depth.setTo(0.0f, band);
  }
  out.person_share = cv::countNonZero(out.mask) / static_cast<double>(out.mask.total());
  return out;
}

}  // namespace dlslam::synth
