// The dense static map end to end on a synthetic walking sequence, where the
// room and the people are known: SLAM in mode full (the rendered person
// masks as the prior), the keyframes fused at their optimised poses, and the
// model compared with the room's mesh and with the people.

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "dlslam/dense/surface_compare.h"
#include "dlslam/synth/actors.h"
#include "dlslam/synth/sequence.h"
#include "dlslam/system/slam_system.h"

namespace dlslam {
namespace {

struct Rendered {
  double timestamp = 0.0;
  SE3d world_from_cam;
  cv::Mat colour, depth;
  cv::Mat person;  // 255 on people, moving or not
};

// Points every `spacing` metres on the room's static triangles.
std::vector<Eigen::Vector3f> SampleMesh(const synth::Mesh& mesh, float spacing) {
  std::vector<Eigen::Vector3f> samples;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3f a = mesh.positions[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3f b = mesh.positions[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3f c = mesh.positions[static_cast<std::size_t>(t[2])];
    const int n = std::max(1, static_cast<int>(std::ceil(std::max((b - a).norm(), (c - a).norm()) / spacing)));
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) samples.push_back(a + (b - a) * (float(i) / n) + (c - a) * (float(j) / n));
    }
  }
  return samples;
}

// The samples some keyframe saw: in its image, in range, on the rendered
// depth (not hidden) and not behind a person.
std::vector<Eigen::Vector3f> Observed(const std::vector<Eigen::Vector3f>& samples, const std::vector<const Rendered*>& views,
                                      const CameraIntrinsics& camera, double max_depth) {
  std::vector<Eigen::Vector3f> seen;
  for (const Eigen::Vector3f& s : samples) {
    for (const Rendered* view : views) {
      const Eigen::Vector3d p = view->world_from_cam.Inverse() * s.cast<double>();
      if (p.z() < 0.1 || p.z() > max_depth) continue;
      const Eigen::Vector2d uv = camera.Project(p);
      const int u = static_cast<int>(std::lround(uv.x())), v = static_cast<int>(std::lround(uv.y()));
      if (u < 0 || v < 0 || u >= camera.width || v >= camera.height) continue;
      if (view->person.at<std::uint8_t>(v, u) != 0) continue;
      if (std::abs(view->depth.at<float>(v, u) - p.z()) > 0.03) continue;
      seen.push_back(s);
      break;
    }
  }
  return seen;
}

TEST(DenseMapTest, TheStaticRoomWithoutThePeople) {
  synth::SynthOptions options;
  options.preset = synth::Preset::kWalkingXyz;
  options.frames = 100;
  options.seed = 2;
  const synth::SynthSequence sequence(options);
  std::vector<Rendered> frames;
  for (int i = 0; i < sequence.size(); ++i) {
    const synth::RenderedFrame f = sequence.Render(i);
    Rendered r;
    r.timestamp = sequence.camera_path()[static_cast<std::size_t>(i)].timestamp;
    r.world_from_cam = sequence.camera_path()[static_cast<std::size_t>(i)].world_from_cam();
    r.colour = f.colour;
    r.depth = f.depth;
    r.person = cv::Mat(f.mask.size(), CV_8UC1);
    for (int y = 0; y < f.mask.rows; ++y) {
      for (int x = 0; x < f.mask.cols; ++x) {
        r.person.at<std::uint8_t>(y, x) = synth::MaskClass(f.mask.at<std::uint8_t>(y, x)) == synth::kClassPerson ? 255 : 0;
      }
    }
    frames.push_back(std::move(r));
  }
  SystemOptions slam_options;
  slam_options.sequential = true;
  slam_options.dynamic.mode = DynamicMode::kFull;
  slam_options.semantic.network = false;
  slam_options.keep_keyframe_images = true;
  SlamSystem slam(options.camera, slam_options);
  std::map<double, const Rendered*> by_time;
  for (const Rendered& f : frames) {
    by_time[f.timestamp] = &f;
    slam.TrackRgbd(f.colour, f.depth, f.timestamp, f.person);
  }
  slam.Shutdown();
  ASSERT_EQ(slam.Stats().frames_tracked, static_cast<int>(frames.size()));
  const auto people = [&by_time](double t) { return by_time.at(t)->person; };
  const dense::TsdfOptions tsdf;
  const std::vector<dense::SurfacePoint> model = slam.FuseDenseMap(tsdf, people).ExtractSurface();
  const std::vector<dense::SurfacePoint> with_people =
      slam.FuseDenseMap(tsdf, people, /*leave_out_removed=*/false).ExtractSurface();
  const auto people_share = [](const std::vector<dense::SurfacePoint>& points) {
    std::size_t n = 0;
    for (const dense::SurfacePoint& p : points) n += p.tagged_share >= 0.5f;
    return static_cast<double>(n) / static_cast<double>(std::max<std::size_t>(points.size(), 1));
  };
  // People in the model: none once the removed regions are left out; without
  // that, the walkers are a few percent of it.
  EXPECT_LT(people_share(model), 0.001);
  EXPECT_GT(people_share(with_people), 0.01);

  // Against the room: the SLAM world is the first camera's frame.
  const SE3d synth_from_slam = frames.front().world_from_cam;
  std::vector<Eigen::Vector3f> points;
  for (const dense::SurfacePoint& p : model) points.push_back((synth_from_slam * p.position.cast<double>()).cast<float>());
  std::vector<const Rendered*> views;
  for (const StampedPose& k : slam.KeyFrameTrajectory()) views.push_back(by_time.at(k.timestamp));
  const std::vector<Eigen::Vector3f> reference =
      Observed(SampleMesh(sequence.scene().static_mesh, 0.02f), views, options.camera, tsdf.max_depth);
  ASSERT_GT(reference.size(), 10000u);
  const dense::SurfaceComparison c = dense::CompareSurfaces(points, reference, 0.02);
  RecordProperty("accuracy_median_mm", static_cast<int>(c.accuracy_median * 1000));
  RecordProperty("completeness_percent", static_cast<int>(c.completeness * 100));
  std::printf("people share %.4f (with the removed regions fused: %.4f)\n", people_share(model), people_share(with_people));
  std::printf("dense map: %zu points, accuracy median %.4f m, p90 %.4f m, completeness %.3f of %zu observed samples\n",
              c.model_points, c.accuracy_median, c.accuracy_p90, c.completeness, c.reference_points);
  // Half a voxel (2 cm voxels) plus the trajectory's few millimetres;
  // complete within a voxel where the keyframes saw the room.
  EXPECT_LT(c.accuracy_median, 0.012);
  EXPECT_LT(c.accuracy_p90, 0.03);
  EXPECT_GT(c.completeness, 0.8);
}

}  // namespace
}  // namespace dlslam
