#include "dlslam/dense/tsdf_volume.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include <opencv2/imgproc.hpp>

#include "dlslam/util/check.h"

namespace dlslam::dense {

namespace {

constexpr int kBlockSide = 8;  // voxels per block edge
constexpr int kBlockVoxels = kBlockSide * kBlockSide * kBlockSide;

// 21 bits per axis: +-1e6 blocks, +-16 km at 2 cm voxels.
constexpr int kKeyBits = 21;
constexpr std::int64_t kKeyOffset = std::int64_t{1} << (kKeyBits - 1);
constexpr std::int64_t kKeyMask = (std::int64_t{1} << kKeyBits) - 1;

std::int64_t Pack(const Eigen::Vector3i& b) {
  return ((b.x() + kKeyOffset) & kKeyMask) | (((b.y() + kKeyOffset) & kKeyMask) << kKeyBits) |
         (((b.z() + kKeyOffset) & kKeyMask) << (2 * kKeyBits));
}

Eigen::Vector3i Unpack(std::int64_t key) {
  return {static_cast<int>((key & kKeyMask) - kKeyOffset), static_cast<int>(((key >> kKeyBits) & kKeyMask) - kKeyOffset),
          static_cast<int>(((key >> (2 * kKeyBits)) & kKeyMask) - kKeyOffset)};
}

int FloorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

void CheckImage(const cv::Mat& image, int type, const CameraIntrinsics& camera, const char* what) {
  if (image.type() != type || image.cols != camera.width || image.rows != camera.height) {
    throw Error(fmt::format("TSDF fusion: the {} image is {}x{} of type {}, expected {}x{} of type {}", what,
                            image.cols, image.rows, image.type(), camera.width, camera.height, type));
  }
}

}  // namespace

struct TsdfVolume::Voxel {
  float tsdf = 0.0f;     // signed distance / truncation, in [-1, 1]
  float weight = 0.0f;   // views fused (capped at max_weight)
  float tagged = 0.0f;   // running share of the weight from tagged pixels
  std::array<std::uint8_t, 3> bgr{0, 0, 0};
};

struct TsdfVolume::Block {
  std::array<Voxel, kBlockVoxels> voxels;
};

void TsdfOptions::Check() const {
  DLSLAM_CHECK(voxel_size >= 1e-3 && voxel_size <= 1.0, "TsdfOptions::voxel_size {} m outside [0.001, 1]", voxel_size);
  DLSLAM_CHECK(truncation >= voxel_size && truncation <= 100 * voxel_size,
               "TsdfOptions::truncation {} m must be 1 to 100 voxels ({} m)", truncation, voxel_size);
  DLSLAM_CHECK(max_depth > 0 && max_depth <= 100, "TsdfOptions::max_depth {} m outside (0, 100]", max_depth);
  DLSLAM_CHECK(allocation_stride >= 1 && allocation_stride <= 64, "TsdfOptions::allocation_stride {} outside [1, 64]",
               allocation_stride);
  DLSLAM_CHECK(exclusion_margin_px >= 0 && exclusion_margin_px <= 200,
               "TsdfOptions::exclusion_margin_px {} outside [0, 200]", exclusion_margin_px);
  DLSLAM_CHECK(min_weight >= 0 && min_weight <= max_weight && max_weight >= 1 && max_weight <= 1e6,
               "TsdfOptions: weights min {} max {} need 0 <= min <= max, 1 <= max <= 1e6", min_weight, max_weight);
}

TsdfVolume::TsdfVolume(const CameraIntrinsics& camera, const TsdfOptions& options)
    : camera_(camera), options_(options) {
  camera_.Check();
  options_.Check();
  rays_ = PixelRays(camera_);
}

TsdfVolume::~TsdfVolume() = default;
TsdfVolume::TsdfVolume(TsdfVolume&&) noexcept = default;
TsdfVolume& TsdfVolume::operator=(TsdfVolume&&) noexcept = default;

TsdfVolume::Block& TsdfVolume::BlockAt(BlockKey key) {
  std::unique_ptr<Block>& block = blocks_[key];
  if (!block) block = std::make_unique<Block>();
  return *block;
}

const TsdfVolume::Block* TsdfVolume::FindBlock(const Eigen::Vector3i& block) const {
  const auto it = blocks_.find(Pack(block));
  return it == blocks_.end() ? nullptr : it->second.get();
}

void TsdfVolume::Integrate(const SE3d& cam_from_world, const cv::Mat& depth, const cv::Mat& colour,
                           const cv::Mat& excluded, const cv::Mat& tag) {
  CheckImage(depth, CV_32FC1, camera_, "depth");
  if (!colour.empty()) CheckImage(colour, CV_8UC3, camera_, "colour");
  if (!excluded.empty()) CheckImage(excluded, CV_8UC1, camera_, "excluded-regions");
  if (!tag.empty()) CheckImage(tag, CV_8UC1, camera_, "tag");
  cv::Mat grown;
  if (!excluded.empty() && options_.exclusion_margin_px > 0) {
    const int k = 2 * options_.exclusion_margin_px + 1;
    cv::dilate(excluded, grown, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
  } else {
    grown = excluded;
  }
  const auto usable = [&](int u, int v, float* d) {
    *d = depth.at<float>(v, u);
    if (!(*d > 0.0f) || *d > options_.max_depth) return false;  // also NaN
    return grown.empty() || grown.at<std::uint8_t>(v, u) == 0;
  };
  const double voxel = options_.voxel_size;
  const double block_size = voxel * kBlockSide;
  const SE3d world_from_cam = cam_from_world.Inverse();

  // 1. Blocks around the observed surface, sampled along each ray within the truncation band.
  const double step = 0.5 * block_size;
  for (int v = 0; v < camera_.height; v += options_.allocation_stride) {
    for (int u = 0; u < camera_.width; u += options_.allocation_stride) {
      float d = 0.0f;
      if (!usable(u, v, &d)) continue;
      const Eigen::Vector2f& ray = rays_[static_cast<std::size_t>(v * camera_.width + u)];
      const Eigen::Vector3d direction(ray.x(), ray.y(), 1.0);
      for (double z = std::max(d - options_.truncation, 1e-3); z <= d + options_.truncation + 1e-9; z += step) {
        const Eigen::Vector3d p = world_from_cam * (direction * z);
        const Eigen::Vector3i b(static_cast<int>(std::floor(p.x() / block_size)),
                                static_cast<int>(std::floor(p.y() / block_size)),
                                static_cast<int>(std::floor(p.z() / block_size)));
        BlockAt(Pack(b));
      }
    }
  }

  // 2. Every voxel of every block in view: projected into the depth image.
  const Eigen::Matrix3d rotation = cam_from_world.so3().matrix();
  const Eigen::Vector3d translation = cam_from_world.translation();
  const double half_diagonal = 0.5 * std::sqrt(3.0) * block_size;
  const double truncation = options_.truncation;
  const float max_weight = static_cast<float>(options_.max_weight);
  for (auto& [key, block] : blocks_) {
    const Eigen::Vector3i b = Unpack(key);
    const Eigen::Vector3d origin = b.cast<double>() * block_size;
    const Eigen::Vector3d centre = rotation * (origin + Eigen::Vector3d::Constant(0.5 * block_size)) + translation;
    if (centre.z() < -half_diagonal || centre.z() > options_.max_depth + truncation + half_diagonal) continue;
    if (centre.z() > half_diagonal) {  // cull blocks clearly outside the image
      const Eigen::Vector2d c = camera_.Project(centre);
      const double margin = half_diagonal / (centre.z() - half_diagonal) * std::max(camera_.fx, camera_.fy) + 2;
      if (c.x() < -margin || c.y() < -margin || c.x() > camera_.width + margin || c.y() > camera_.height + margin) {
        continue;
      }
    }
    for (int i = 0; i < kBlockVoxels; ++i) {
      const Eigen::Vector3d local((i % kBlockSide + 0.5) * voxel, ((i / kBlockSide) % kBlockSide + 0.5) * voxel,
                                  (i / (kBlockSide * kBlockSide) + 0.5) * voxel);
      const Eigen::Vector3d p = rotation * (origin + local) + translation;
      if (p.z() <= 1e-3) continue;
      Eigen::Vector2d xn(p.x() / p.z(), p.y() / p.z());
      if (camera_.HasDistortion()) xn = camera_.Distort(xn);
      const int u = static_cast<int>(std::lround(camera_.fx * xn.x() + camera_.cx));
      const int v = static_cast<int>(std::lround(camera_.fy * xn.y() + camera_.cy));
      if (u < 0 || v < 0 || u >= camera_.width || v >= camera_.height) continue;
      float d = 0.0f;
      if (!usable(u, v, &d)) continue;
      // Projective distance along the ray, scaled from depth to range.
      const double ray_scale = std::sqrt(1.0 + xn.squaredNorm());
      const double sdf = (d - p.z()) * ray_scale;
      if (sdf < -truncation) continue;  // behind the surface: unseen
      const float observed = static_cast<float>(std::min(1.0, sdf / truncation));
      Voxel& voxel_ref = block->voxels[static_cast<std::size_t>(i)];
      const float w = voxel_ref.weight;
      const float w1 = w + 1.0f;
      voxel_ref.tsdf = (voxel_ref.tsdf * w + observed) / w1;
      const bool tagged = !tag.empty() && tag.at<std::uint8_t>(v, u) != 0;
      voxel_ref.tagged = (voxel_ref.tagged * w + (tagged ? 1.0f : 0.0f)) / w1;
      // Colour only near the surface: free-space updates see what is behind.
      if (!colour.empty() && std::abs(observed) < 1.0f) {
        const cv::Vec3b c = colour.at<cv::Vec3b>(v, u);
        for (int k = 0; k < 3; ++k) {
          voxel_ref.bgr[static_cast<std::size_t>(k)] =
              static_cast<std::uint8_t>(std::lround((voxel_ref.bgr[static_cast<std::size_t>(k)] * w + c[k]) / w1));
        }
      }
      voxel_ref.weight = std::min(w1, max_weight);
    }
  }
}

std::vector<SurfacePoint> TsdfVolume::ExtractSurface() const {
  std::vector<SurfacePoint> points;
  const double voxel = options_.voxel_size;
  const float min_weight = static_cast<float>(std::max(options_.min_weight, 1e-6));
  const auto voxel_at = [this](const Eigen::Vector3i& g) -> const Voxel* {
    const Eigen::Vector3i b(FloorDiv(g.x(), kBlockSide), FloorDiv(g.y(), kBlockSide), FloorDiv(g.z(), kBlockSide));
    const Block* block = FindBlock(b);
    if (!block) return nullptr;
    const Eigen::Vector3i l = g - b * kBlockSide;
    return &block->voxels[static_cast<std::size_t>(l.x() + kBlockSide * (l.y() + kBlockSide * l.z()))];
  };
  for (const auto& [key, block] : blocks_) {
    const Eigen::Vector3i b = Unpack(key);
    for (int i = 0; i < kBlockVoxels; ++i) {
      const Voxel& a = block->voxels[static_cast<std::size_t>(i)];
      if (a.weight < min_weight || std::abs(a.tsdf) >= 1.0f) continue;
      const Eigen::Vector3i g =
          b * kBlockSide + Eigen::Vector3i(i % kBlockSide, (i / kBlockSide) % kBlockSide, i / (kBlockSide * kBlockSide));
      for (int axis = 0; axis < 3; ++axis) {
        const Eigen::Vector3i n = g + Eigen::Vector3i::Unit(axis);
        const Voxel* c = voxel_at(n);
        if (!c || c->weight < min_weight || std::abs(c->tsdf) >= 1.0f) continue;
        if ((a.tsdf > 0) == (c->tsdf > 0)) continue;
        const float t = a.tsdf / (a.tsdf - c->tsdf);  // in [0, 1]
        const Eigen::Vector3f pa = ((g.cast<double>() + Eigen::Vector3d::Constant(0.5)) * voxel).cast<float>();
        SurfacePoint point;
        point.position = pa + t * static_cast<float>(voxel) * Eigen::Vector3f::Unit(axis);
        point.bgr = (t < 0.5f ? a : *c).bgr;
        point.tagged_share = (1.0f - t) * a.tagged + t * c->tagged;
        points.push_back(point);
      }
    }
  }
  return points;
}

std::size_t TsdfVolume::NumBlocks() const { return blocks_.size(); }

std::size_t TsdfVolume::MemoryBytes() const { return blocks_.size() * (sizeof(Block) + 32); }

}  // namespace dlslam::dense
