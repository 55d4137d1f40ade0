#include "dlslam/synth/texture.h"

#include <opencv2/imgproc.hpp>

#include "dlslam/util/check.h"

namespace dlslam::synth {

namespace {
bool IsPowerOfTwo(int n) { return n > 0 && (n & (n - 1)) == 0; }
}  // namespace

Texture Texture::FromImage(const cv::Mat& bgr) {
  DLSLAM_CHECK_EQ(bgr.type(), CV_8UC3, "texture must be 8-bit BGR");
  DLSLAM_CHECK(IsPowerOfTwo(bgr.cols) && IsPowerOfTwo(bgr.rows),
               "texture size {}x{} is not a power of two", bgr.cols, bgr.rows);
  Texture t;
  t.levels.push_back(bgr.clone());
  while (t.levels.back().cols >= 8 && t.levels.back().rows >= 8) {
    cv::Mat next;
    // pyrDown's 5x5 Gaussian treats the border by reflection; the wrap seam
    // differs slightly, which at these sizes nobody can see.
    cv::pyrDown(t.levels.back(), next);
    t.levels.push_back(next);
  }
  return t;
}

}  // namespace dlslam::synth
