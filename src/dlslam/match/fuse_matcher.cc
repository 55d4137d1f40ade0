#include "dlslam/match/fuse_matcher.h"

#include <cmath>
#include <unordered_set>

#include "dlslam/match/point_visibility.h"
#include "dlslam/util/check.h"

namespace dlslam {

void FuseMatchOptions::Check() const {
  DLSLAM_CHECK_GT(radius, 0.0);
  DLSLAM_CHECK(max_distance > 0 && max_distance <= 256, "max_distance {} outside (0, 256]", max_distance);
  DLSLAM_CHECK_GT(chi2_mono, 0.0);
  DLSLAM_CHECK_GT(chi2_stereo, 0.0);
  DLSLAM_CHECK(max_view_angle_deg > 0 && max_view_angle_deg <= 180);
}

std::vector<FuseCandidate> SearchForFusion(const Frame& frame, const SE3d& cam_from_world,
                                           const std::vector<MapPointId>& keyframe_points,
                                           const std::vector<MapPointView>& points,
                                           const FuseMatchOptions& options) {
  options.Check();
  DLSLAM_CHECK_EQ(keyframe_points.size(), frame.size());
  const std::unordered_set<MapPointId> seen(keyframe_points.begin(), keyframe_points.end());
  const CameraIntrinsics& cam = frame.camera();
  const ScalePyramid& pyr = frame.pyramid();
  const PointVisibility visibility(cam, cam_from_world, options.max_view_angle_deg);
  std::vector<FuseCandidate> out;
  std::vector<int> candidates;
  for (const MapPointView& p : points) {
    if (seen.count(p.id)) continue;
    const std::optional<VisibleProjection> visible = visibility.Project(p);
    if (!visible) continue;
    const Eigen::Vector3d& pc = visible->point_cam;
    const Eigen::Vector2d& uv = visible->uv;
    const double dist = visible->distance;
    const int octave = PredictOctave(dist, p.max_distance, pyr);
    const double right_u = uv.x() - cam.bf / pc.z();
    int best = options.max_distance + 1, best_idx = -1;
    frame.FeaturesInArea(uv.x(), uv.y(), options.radius * pyr.Scale(octave), std::max(octave - 1, 0), octave,
                         candidates);
    for (int idx : candidates) {
      const FrameKeypoint& k = frame.keypoint(idx);
      const double info = pyr.InverseSigma2(k.octave);
      double chi2 = (k.uv - uv).squaredNorm();
      if (k.right_u >= 0) chi2 += (k.right_u - right_u) * (k.right_u - right_u);
      if (chi2 * info > (k.right_u >= 0 ? options.chi2_stereo : options.chi2_mono)) continue;
      const int d = HammingDistance(p.descriptor.data(), frame.descriptor(idx));
      if (d < best) {
        best = d;
        best_idx = idx;
      }
    }
    if (best_idx >= 0) out.push_back({p.id, best_idx});
  }
  return out;
}

}  // namespace dlslam
