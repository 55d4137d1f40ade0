#include "dlslam/features/test_images.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <random>

#include "tests/support/test_data.h"

namespace dlslam::features::testing {

cv::Mat SyntheticTexture(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> grey(0, 255), x(0, width - 1), y(0, height - 1);
  std::uniform_int_distribution<int> extent(4, 40), angle(0, 179);
  cv::Mat image(height, width, CV_8UC1, cv::Scalar(128));
  for (int i = 0; i < width * height / 300; ++i) {
    const cv::Point centre(x(rng), y(rng));
    const cv::Size axes(extent(rng), extent(rng));
    if (i % 2 == 0) {
      cv::rectangle(image, cv::Rect(centre, axes), cv::Scalar(grey(rng)), cv::FILLED);
    } else {
      cv::ellipse(image, centre, axes, angle(rng), 0, 360, cv::Scalar(grey(rng)), cv::FILLED);
    }
  }
  cv::GaussianBlur(image, image, cv::Size(3, 3), 0.8);
  return image;
}

std::optional<cv::Mat> RealFrame(const std::string& name) {
  const auto root = dlslam::testing::SharedDataDir();
  if (!root) return std::nullopt;
  const std::filesystem::path path = *root / "7scenes-redkitchen-500" / "rgb" / name;
  if (!std::filesystem::exists(path)) return std::nullopt;
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
  if (image.empty()) return std::nullopt;
  return image;
}

}  // namespace dlslam::features::testing
