#pragma once
// Textures: an 8-bit BGR image with its mip pyramid, sampled bilinearly with
// wrap-around. The renderer picks the mip level from the pixel's footprint on
// the surface, so distant surfaces stay stable from frame to frame instead of
// aliasing into noise (which would hurt feature matching across frames).

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace dlslam::synth {

struct Texture {
  // levels[0]: full resolution; each next level half the size. Width and
  // height are powers of two (wrap-around by masking).
  std::vector<cv::Mat> levels;  // CV_8UC3, BGR
  float texels_per_metre = 200.0f;  // the density it was drawn for (materials default to it)

  // Builds the pyramid from a power-of-two image (throws dlslam::Error otherwise).
  static Texture FromImage(const cv::Mat& bgr);

  int max_level() const { return static_cast<int>(levels.size()) - 1; }

  // Colour at texel coordinates (x, y) of level 0 (texel centres at +0.5),
  // read from mip level `level` with bilinear filtering. Out: B, G, R in [0, 255].
  void Sample(float x, float y, int level, float out[3]) const {
    level = std::clamp(level, 0, max_level());
    const cv::Mat& img = levels[static_cast<std::size_t>(level)];
    const float scale = 1.0f / static_cast<float>(1 << level);
    const float fx = x * scale - 0.5f;
    const float fy = y * scale - 0.5f;
    const float x0f = std::floor(fx);
    const float y0f = std::floor(fy);
    const float ax = fx - x0f;
    const float ay = fy - y0f;
    const int wmask = img.cols - 1;
    const int hmask = img.rows - 1;
    // Large coordinates are fine: masking an int wraps them (two's complement).
    const int x0 = static_cast<int>(x0f) & wmask;
    const int x1 = (x0 + 1) & wmask;
    const int y0 = static_cast<int>(y0f) & hmask;
    const int y1 = (y0 + 1) & hmask;
    const unsigned char* r0 = img.ptr<unsigned char>(y0);
    const unsigned char* r1 = img.ptr<unsigned char>(y1);
    for (int c = 0; c < 3; ++c) {
      const float top = r0[3 * x0 + c] + ax * (r0[3 * x1 + c] - r0[3 * x0 + c]);
      const float bottom = r1[3 * x0 + c] + ax * (r1[3 * x1 + c] - r1[3 * x0 + c]);
      out[c] = top + ay * (bottom - top);
    }
  }
};

// How a surface uses a texture.
struct Material {
  int texture = 0;                  // index into Scene::textures
  float texels_per_metre = 200.0f;  // [texel/m] at level 0
  float offset_x = 0.0f;            // [texel] shift, so objects show different patches
  float offset_y = 0.0f;
  float tint[3] = {1.0f, 1.0f, 1.0f};  // B, G, R multipliers
};

}  // namespace dlslam::synth
