#pragma once
// Semi-real sequences: real photos of people (cut out by their masks) walked
// through a real static RGB-D recording with known poses. Each person is a
// vertical billboard standing in the world, turned towards the camera, with a
// body-like depth profile (thickest at the torso, thin at the outline); it
// walks back and forth along a line, occludes the real scene and is occluded
// by whatever real surface is nearer, and gets structured-light-like depth
// (noise growing with z^2, no depth along its outline). The ground-truth mask
// of every frame marks the people as moving (synth::MaskValue). No I/O here:
// `dlslam composite` reads the recording and the cut-outs and writes the result.
//
//   PeopleCompositor people(camera, cutouts, options, camera_path);
//   CompositedFrame f = people.Composite(t, world_from_cam, colour, depth_m);

#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/data/trajectory.h"
#include "dlslam/geometry/se3.h"

namespace dlslam::synth {

// A photo of one person and its mask (CV_8UC3 BGR, CV_8UC1 non-zero = person).
struct Cutout {
  cv::Mat bgr;
  cv::Mat mask;
  std::string name;  // for messages
};

struct CompositeOptions {
  // People walking at once [1, 20].
  int people = 2;
  // Each walks along a line in front of the camera of a random frame (so
  // that people are met along the whole recording), a random distance in
  // [min, max] from it [m].
  double min_distance_m = 1.0;
  double max_distance_m = 2.5;
  // Walking speed [m/s] and the length of the line walked back and forth [m].
  double speed_mps = 1.0;
  double path_length_m = 3.0;
  // Person height [m]: mean and the half-width of its uniform spread.
  double height_m = 1.75;
  double height_spread_m = 0.1;
  // Front-to-back thickness of the body's depth profile [m].
  double body_depth_m = 0.25;
  // Depth noise sigma = noise_per_m2 * z^2 [1/m] on the people (Kinect / Xtion:
  // ~1.4e-3), and a band without depth along their outline [px], as
  // structured-light sensors leave at depth edges.
  double noise_per_m2 = 1.4e-3;
  int outline_hole_px = 2;
  unsigned seed = 1;

  // Throws dlslam::Error naming the field and its value.
  void Check() const;
};

struct CompositedFrame {
  cv::Mat colour;  // CV_8UC3
  cv::Mat depth;   // CV_32FC1 metres
  cv::Mat mask;    // CV_8UC1: MaskValue(kClassPerson, true) on people, 0 elsewhere
  double person_share = 0;  // of the image covered by people
};

class PeopleCompositor {
 public:
  // `camera_path`: the recording's poses (world_from_cam) and times; "up"
  // is the first camera's -y axis, the walkers start at its time. Throws
  // dlslam::Error for no cut-outs or poses, a cut-out whose mask is empty or
  // of another size, or bad options.
  PeopleCompositor(const CameraIntrinsics& camera, std::vector<Cutout> cutouts, const CompositeOptions& options,
                   const Trajectory& camera_path);

  // The people at time t seen from `world_from_cam`, composited into the
  // real frame (colour CV_8UC3 BGR, depth CV_32FC1 metres, 0 = none; camera size).
  CompositedFrame Composite(double t, const SE3d& world_from_cam, const cv::Mat& colour, const cv::Mat& depth) const;

  int walkers() const { return static_cast<int>(walkers_.size()); }

 private:
  struct Walker {
    int cutout = 0;
    double height = 1.75, width = 0.5;  // billboard size [m]
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();  // centre of the line, at the billboard's centre height
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // along the line (horizontal, unit)
    double phase_m = 0;  // where on its back-and-forth it starts
  };
  struct PreparedCutout {
    cv::Mat bgr, mask;  // cropped to the mask's bounding box
    cv::Mat thickness;  // CV_32FC1 in [0, 1]: 0 at the outline, 1 inside the torso
  };
  Eigen::Vector3d PositionAt(const Walker& w, double t) const;

  CameraIntrinsics camera_;
  CompositeOptions options_;
  std::vector<PreparedCutout> cutouts_;
  std::vector<Walker> walkers_;
  Eigen::Vector3d up_ = Eigen::Vector3d::UnitY();
  double first_t_ = 0;
  std::vector<Eigen::Vector2f> rays_;  // undistorted (x/z, y/z) per pixel
};

}  // namespace dlslam::synth
