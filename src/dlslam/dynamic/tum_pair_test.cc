// The multi-view check on two real TUM fr3/walking_xyz frames (3 s apart)
// with ground-truth poses: reference keyframe = frame 1, current = frame 2.
// The walking people must be flagged; DynaSLAM's mask of frame 2 serves as a
// loose reference (dilated: it hugs the silhouettes, ours follows depth).

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "dlslam/dynamic/tools/keyframe_eval.h"
#include "dlslam/io/image_io.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/synth/camera_path.h"
#include "tests/support/test_data.h"

namespace dlslam::dynamic {
namespace {

io::ImageSource Source(const std::filesystem::path& path) {
  io::ImageSource source;
  source.image = path;
  return source;
}

TEST(GeometryOnTum, WalkingPeopleAreFlagged) {
  DLSLAM_REQUIRE_SHARED_DATA(dir, "real-samples/tum_walking_xyz_3frames");
  DLSLAM_REQUIRE_SHARED_DATA(gt_path, "tum/gt/rgbd_dataset_freiburg3_walking_xyz.txt");
  const CameraIntrinsics camera = CameraPreset("freiburg3");
  const Trajectory gt = io::ReadTumTrajectory(gt_path);
  const double t0 = 1341846313.592026, t1 = 1341846316.570121;
  // Frame 1 is 46 ms before the first ground-truth pose (the camera moves
  // ~0.2 m/s: ~1 cm); take that pose for it.
  ASSERT_NEAR(gt.front().timestamp, t0, 0.05);
  const std::optional<SE3d> pose0 = gt.front().world_from_cam();
  const std::optional<SE3d> pose1 = synth::InterpolatePose(gt, t1);
  ASSERT_TRUE(pose1);
  const cv::Mat colour0 = io::ReadColorImage(Source(dir / "rgb/1341846313.592026.png"), 640, 480);
  const cv::Mat depth0 =
      io::ReadDepthImage(Source(dir / "depth/1341846313.592088.png"), 5000, 640, 480);
  const cv::Mat depth1 =
      io::ReadDepthImage(Source(dir / "depth/1341846316.570146.png"), 5000, 640, 480);
  const cv::Mat dynaslam =
      cv::imread((dir / "dynaslam_masks/1341846316.570121.png").string(), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(dynaslam.empty());

  features::OrbExtractor orb;
  const ReferenceView reference = evaluation::MakeReferenceView(
      depth0, orb.Extract(colour0).keypoints, camera, *pose0, 0);
  cv::Mat reference_mask;
  cv::dilate(dynaslam != 0, reference_mask,
             cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(41, 41)));
  for (const SearchKind kind : {SearchKind::kExhaustive, SearchKind::kAntColony}) {
    SCOPED_TRACE(ToString(kind));
    GeometryOptions options;
    options.search = kind;
    GeometryDetector detector(options);
    const GeometryResult r = detector.Detect(depth1, camera, pose1->Inverse(), {reference});
    const int flagged = cv::countNonZero(r.dynamic_mask);
    const int inside = cv::countNonZero(r.dynamic_mask & reference_mask);
    // The people cover ~15% of the frame; a good part of them is flagged ...
    EXPECT_GT(flagged, 0.03 * 640 * 480);
    // ... and most of what is flagged is on them.
    EXPECT_GT(inside, 0.7 * flagged);
    // Dynamic points: mostly inside DynaSLAM's (dilated) mask as well.
    int dynamic_inside = 0;
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      if (r.labels[i] != PointLabel::kDynamic) continue;
      const cv::Point p(cvRound(r.points[i].pixel.x()), cvRound(r.points[i].pixel.y()));
      dynamic_inside += reference_mask.at<std::uint8_t>(p) != 0;
    }
    EXPECT_GT(dynamic_inside, 0.7 * r.points_dynamic);
    RecordProperty("flagged_" + ToString(kind), flagged);
    std::printf("%s: flagged %d px, %.2f inside dilated DynaSLAM mask; dynamic points %d (%.2f inside)\n",
                ToString(kind).c_str(), flagged, static_cast<double>(inside) / flagged,
                r.points_dynamic, static_cast<double>(dynamic_inside) / r.points_dynamic);
  }
}

}  // namespace
}  // namespace dlslam::dynamic
