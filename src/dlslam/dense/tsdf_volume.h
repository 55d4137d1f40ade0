#pragma once
// A dense model of the static scene: the keyframes' depth fused at their
// optimised poses into a truncated signed distance field (projective TSDF,
// as KinectFusion) on a sparse grid of 8x8x8-voxel blocks (voxel hashing),
// with colour. The pixels the dynamic stage removed are never fused, so the
// people are not in the model; a person the masks missed in one view is
// carved away by the later views that see the free space where it stood
// (every voxel of a block in view is updated, not only those near this
// view's surface).
//
//   dense::TsdfVolume volume(camera, options);
//   for (keyframe ...) volume.Integrate(cam_from_world, depth_m, bgr, removed);
//   io::WritePointCloudPly("room.ply", volume.ExtractSurface());
//
// No I/O; not thread-safe (one caller).

#include <array>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "dlslam/data/camera.h"
#include "dlslam/geometry/se3.h"

namespace dlslam::dense {

struct TsdfOptions {
  // Edge of a voxel [m]: 2 cm resolves a chair's legs, a room of 5 x 5 x 3 m
  // takes ~100 MB (only blocks near surfaces exist).
  double voxel_size = 0.02;
  // Distance over which the signed distance is kept [m]; beyond it a voxel
  // is "free" (+1) in front of the surface, unknown behind. ~4 voxels; it
  // must exceed the depth noise (Kinect/Xtion: 1.4e-3 z^2, 2 cm at 4 m).
  double truncation = 0.08;
  // Depth beyond this is not fused [m] (structured-light noise grows with z^2).
  double max_depth = 4.0;
  // Pixel step of the ray sampling that allocates new blocks [px]; the
  // voxels themselves are updated from every pixel they project to.
  int allocation_stride = 2;
  // A voxel is on the surface only after this many views (weight): a single
  // view's outliers and a mover seen once stay out. (3 on the semi-real
  // kitchen with the network: people 0.96 % of the model instead of 1.55 %,
  // but 26 % fewer points.)
  double min_weight = 2.0;
  // Weights stop growing here, so that a changed scene can still be updated.
  double max_weight = 64.0;
  // The excluded regions are grown by this many pixels before fusing (a
  // segmentation is least sure at a person's outline). 0: on the semi-real
  // kitchen with the network, 8 px took the people's share of the model
  // only from 1.55 % to 1.53 % and cost 8 % of the points.
  int exclusion_margin_px = 0;

  // Throws dlslam::Error naming the bad value.
  void Check() const;
};

struct SurfacePoint {
  Eigen::Vector3f position;      // world [m]
  std::array<std::uint8_t, 3> bgr;
  // Share of the voxel's weight fused from tagged pixels (Integrate's `tag`,
  // e.g. ground-truth people: how much of a mover got into the model).
  float tagged_share = 0.0f;
};

class TsdfVolume {
 public:
  // `camera`: the images' intrinsics and distortion (depth registered to colour).
  TsdfVolume(const CameraIntrinsics& camera, const TsdfOptions& options = {});
  ~TsdfVolume();
  TsdfVolume(TsdfVolume&&) noexcept;
  TsdfVolume& operator=(TsdfVolume&&) noexcept;

  // Fuses one view. `depth`: CV_32FC1 metres (0 or non-finite = none);
  // `colour`: CV_8UC3 BGR or empty (grey model); `excluded`: CV_8UC1,
  // non-zero = not fused (the removed dynamic regions), or empty; `tag`:
  // CV_8UC1, non-zero pixels counted in SurfacePoint::tagged_share, or
  // empty. Images at the camera's size; throws dlslam::Error otherwise.
  void Integrate(const SE3d& cam_from_world, const cv::Mat& depth, const cv::Mat& colour,
                 const cv::Mat& excluded = cv::Mat(), const cv::Mat& tag = cv::Mat());

  // Points where the signed distance crosses zero between neighbouring
  // voxels that both reached min_weight, interpolated; one per crossing
  // edge (about one per voxel of surface).
  std::vector<SurfacePoint> ExtractSurface() const;

  std::size_t NumBlocks() const;
  std::size_t MemoryBytes() const;
  const TsdfOptions& options() const { return options_; }

 private:
  struct Voxel;
  struct Block;
  using BlockKey = std::int64_t;

  Block& BlockAt(BlockKey key);
  const Block* FindBlock(const Eigen::Vector3i& block) const;

  CameraIntrinsics camera_;
  TsdfOptions options_;
  std::vector<Eigen::Vector2f> rays_;  // undistorted ray of every pixel (PixelRays)
  std::unordered_map<BlockKey, std::unique_ptr<Block>> blocks_;
};

}  // namespace dlslam::dense
