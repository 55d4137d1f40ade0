#include "dlslam/synth/renderer.h"

#include <opencv2/imgproc.hpp>

#include <bit>
#include <cmath>
#include <cstdint>

#include "dlslam/synth/random.h"
#include "dlslam/synth/rasterizer.h"
#include "dlslam/util/check.h"

namespace dlslam::synth {

namespace {

struct LabelInfo {
  int class_id = kClassStatic;
  bool moving = false;
};

// Largest distance any corner of the part's bounding box travelled.
double PartDisplacement(const Mesh& mesh, const SE3d& now, const SE3d& before) {
  const Eigen::Vector3d lo = mesh.BoundsMin().cast<double>(), hi = mesh.BoundsMax().cast<double>();
  double worst = 0;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d c((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
    worst = std::max(worst, (now * c - before * c).norm());
  }
  return worst;
}

// Draws everything visible at scene time t. labels[0] is the static world;
// every actor part gets its own label after it.
void Rasterize(const Scene& scene, const CameraIntrinsics& camera, const SE3d& world_from_cam, double t,
               const RenderOptions& options, GBuffer& buf, std::vector<LabelInfo>& labels) {
  buf.Reset(camera.width, camera.height);
  labels.assign(1, LabelInfo{});
  const SE3d cam_from_world = world_from_cam.Inverse();
  RasterLight light;
  light.direction_cam = (cam_from_world.rotationMatrix() * scene.light_direction.normalized()).cast<float>();
  auto draw = [&](const Mesh& mesh, const SE3d& cam_from_object, int label) {
    RasterizeMesh(mesh, cam_from_object.rotationMatrix().cast<float>(), cam_from_object.translation().cast<float>(),
                  camera, label, light, options.near_m, buf);
  };
  draw(scene.static_mesh, cam_from_world, 0);
  for (const Actor& actor : scene.actors) {
    const std::vector<SE3d> now = actor.pose_at(t);
    const std::vector<SE3d> before = actor.pose_at(t - options.moving_interval_s);
    DLSLAM_CHECK_EQ(now.size(), actor.parts.size(), "actor '{}' gave a pose per part", actor.kind);
    for (std::size_t k = 0; k < actor.parts.size(); ++k) {
      const ActorPart& part = actor.parts[k];
      const bool moving = PartDisplacement(part.mesh, now[k], before[k]) > options.moving_threshold_m;
      labels.push_back({part.class_id, moving});
      draw(part.mesh, cam_from_world * now[k], static_cast<int>(labels.size()) - 1);
    }
  }
}

// floor(log2(x)) from the float's exponent bits, 0 for x < 2 (and NaN).
int MipLevel(float x) {
  if (!(x >= 2.0f)) return 0;
  return static_cast<int>((std::bit_cast<std::uint32_t>(x) >> 23) & 0xFFu) - 127;
}

// Texture, mip level and flat Lambert shading per pixel; float BGR.
void Shade(const Scene& scene, const CameraIntrinsics& camera, const GBuffer& buf, double mip_bias, cv::Mat& out) {
  out.create(buf.height, buf.width, CV_32FC3);
  const float inv_f = static_cast<float>(1.0 / camera.fx);
  // Rounding log2 to the nearest level: floor(log2(x) + 0.5 + bias) = floor(log2(x * 2^(0.5 + bias))).
  const float bias = std::exp2(static_cast<float>(mip_bias) + 0.5f);
  for (int y = 0; y < buf.height; ++y) {
    cv::Vec3f* row = out.ptr<cv::Vec3f>(y);
    for (int x = 0; x < buf.width; ++x) {
      const int i = y * buf.width + x;
      const int tri = buf.triangle[i];
      if (tri < 0) {
        row[x] = cv::Vec3f(0, 0, 0);
        continue;
      }
      const TriangleRecord& rec = buf.records[static_cast<std::size_t>(tri)];
      const Material& m = scene.materials[static_cast<std::size_t>(rec.material)];
      const Texture& tex = scene.textures[static_cast<std::size_t>(m.texture)];
      const float z = 1.0f / buf.inv_depth[i];
      // Texels under one pixel: z / f metres per pixel, stretched on slanted surfaces.
      const float footprint = m.texels_per_metre * z * inv_f / rec.slant;
      const int level = MipLevel(footprint * bias);
      float c[3];
      tex.Sample(buf.u[i] * m.texels_per_metre + m.offset_x, buf.v[i] * m.texels_per_metre + m.offset_y,
                 level, c);
      row[x] = cv::Vec3f(c[0] * rec.shade * m.tint[0], c[1] * rec.shade * m.tint[1], c[2] * rec.shade * m.tint[2]);
    }
  }
}

SE3d Interpolate(const SE3d& a, const SE3d& b, double f) {
  return a * SE3d::Exp(f * (a.Inverse() * b).Log());
}

}  // namespace

void RenderOptions::Check() const {
  DLSLAM_CHECK_GT(near_m, 0.0f, "near plane [m]");
  depth.Check();
  DLSLAM_CHECK_GE(colour_noise_sigma, 0.0, "colour noise sigma");
  DLSLAM_CHECK_GE(lens_blur_sigma_px, 0.0, "lens blur sigma [px]");
  DLSLAM_CHECK_GE(motion_blur_samples, 1, "motion blur samples");
  DLSLAM_CHECK_GE(exposure_s, 0.0, "exposure [s]");
  DLSLAM_CHECK_GE(moving_threshold_m, 0.0, "moving threshold [m]");
  DLSLAM_CHECK_GT(moving_interval_s, 0.0, "moving interval [s]");
}

RenderedFrame RenderFrame(const Scene& scene, const CameraIntrinsics& camera, const CameraState& state,
                          const RenderOptions& options, std::mt19937& rng) {
  options.Check();
  camera.Check();
  DLSLAM_CHECK(!camera.HasDistortion(), "camera '{}' has distortion; the renderer draws a pinhole image",
               camera.name);
  RenderedFrame frame;
  frame.world_from_cam = state.world_from_cam;
  frame.scene_time = state.scene_time;
  GBuffer buf;
  std::vector<LabelInfo> labels;
  Rasterize(scene, camera, state.world_from_cam, state.scene_time, options, buf, labels);
  cv::Mat colour_f;
  Shade(scene, camera, buf, options.mip_bias, colour_f);

  frame.true_depth.create(camera.height, camera.width, CV_32FC1);
  frame.mask.create(camera.height, camera.width, CV_8UC1);
  for (int y = 0; y < camera.height; ++y) {
    float* z = frame.true_depth.ptr<float>(y);
    unsigned char* m = frame.mask.ptr<unsigned char>(y);
    for (int x = 0; x < camera.width; ++x) {
      const int i = y * camera.width + x;
      const int tri = buf.triangle[i];
      z[x] = tri < 0 ? 0.0f : 1.0f / buf.inv_depth[i];
      if (tri < 0) {
        m[x] = 0;
      } else {
        const LabelInfo& l = labels[static_cast<std::size_t>(buf.records[static_cast<std::size_t>(tri)].label)];
        m[x] = MaskValue(l.class_id, l.moving);
      }
    }
  }

  if (options.motion_blur_samples > 1 && state.previous_world_from_cam != nullptr && options.exposure_s > 0) {
    // Average instants spread over the exposure, which ends at this frame.
    const int n = options.motion_blur_samples;
    for (int k = 1; k < n; ++k) {
      const double back = options.exposure_s * k / (n - 1);
      const SE3d pose = Interpolate(state.world_from_cam, *state.previous_world_from_cam,
                                    std::min(1.0, back / state.frame_interval_s));
      GBuffer sub_buf;
      std::vector<LabelInfo> sub_labels;
      Rasterize(scene, camera, pose, state.scene_time - back, options, sub_buf, sub_labels);
      cv::Mat sub;
      Shade(scene, camera, sub_buf, options.mip_bias, sub);
      colour_f += sub;
    }
    colour_f *= 1.0 / n;
  }

  colour_f.convertTo(frame.colour, CV_8UC3);
  if (options.lens_blur_sigma_px > 0) {
    cv::GaussianBlur(frame.colour, frame.colour, cv::Size(0, 0), options.lens_blur_sigma_px);
  }
  if (options.colour_noise_sigma > 0) {
    const float* normal = StandardNormalTable();
    const float sigma = static_cast<float>(options.colour_noise_sigma);
    for (int y = 0; y < camera.height; ++y) {
      unsigned char* p = frame.colour.ptr<unsigned char>(y);
      for (int x = 0; x < camera.width * 3; x += 3) {
        const std::uint32_t a = rng(), b = rng();
        const float n[3] = {normal[a & 0xFFFFu], normal[a >> 16], normal[b & 0xFFFFu]};
        for (int c = 0; c < 3; ++c) p[x + c] = cv::saturate_cast<unsigned char>(p[x + c] + sigma * n[c]);
      }
    }
  }
  frame.depth = ApplyDepthNoise(frame.true_depth, options.depth, rng);
  return frame;
}

}  // namespace dlslam::synth
