#include "frame_view_image.h"

#include <fmt/format.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "dlslam/util/check.h"

namespace dlslam::app {

namespace {

void Tint(cv::Mat& image, const cv::Mat& mask, const cv::Scalar& colour) {
  if (mask.empty() || mask.size() != image.size()) return;
  const cv::Mat tint(image.size(), CV_8UC3, colour);
  cv::Mat blended;
  cv::addWeighted(image, 0.6, tint, 0.4, 0.0, blended);
  blended.copyTo(image, mask);
}

}  // namespace

cv::Mat DrawFrameView(const cv::Mat& colour, const SlamSystem::FrameView& view) {
  cv::Mat image;
  if (colour.empty()) {
    image = cv::Mat(480, 640, CV_8UC3, cv::Scalar(40, 40, 40));
  } else if (colour.type() == CV_8UC1) {
    cv::cvtColor(colour, image, cv::COLOR_GRAY2BGR);
  } else {
    image = colour.clone();
  }
  Tint(image, view.prior_mask, cv::Scalar(60, 60, 230));
  if (!view.removed_mask.empty()) {
    cv::Mat added = view.removed_mask.clone();
    if (!view.prior_mask.empty() && view.prior_mask.size() == added.size()) added.setTo(0, view.prior_mask);
    Tint(image, added, cv::Scalar(230, 110, 40));
  }
  for (const cv::Point2f& p : view.kept) cv::circle(image, p, 3, cv::Scalar(60, 200, 60), 1, cv::LINE_AA);
  for (const cv::Point2f& p : view.removed) cv::circle(image, p, 3, cv::Scalar(40, 220, 240), 1, cv::LINE_AA);
  return image;
}

RemovalImageWriter::RemovalImageWriter(std::filesystem::path folder, int every)
    : folder_(std::move(folder)), every_(every) {
  DLSLAM_CHECK(every_ >= 1, "--removal-images-every {} must be at least 1", every_);
  std::error_code error;
  if (std::filesystem::exists(folder_, error) && !std::filesystem::is_directory(folder_, error)) {
    throw Error(fmt::format("--removal-images {}: exists and is not a folder", folder_.string()));
  }
  if (std::filesystem::is_directory(folder_, error) && !std::filesystem::is_empty(folder_, error)) {
    throw Error(fmt::format("--removal-images {}: the folder is not empty (nothing in it is overwritten); give a new "
                            "or empty folder",
                            folder_.string()));
  }
  std::filesystem::create_directories(folder_, error);
  if (error) throw Error(fmt::format("--removal-images {}: cannot create the folder: {}", folder_.string(), error.message()));
}

void RemovalImageWriter::Write(std::size_t index, const std::string& name, const cv::Mat& colour,
                               const SlamSystem::FrameView& view) {
  if (index % static_cast<std::size_t>(every_) != 0) return;
  const std::filesystem::path file = folder_ / (name + ".jpg");
  bool ok = false;
  try {
    ok = cv::imwrite(file.string(), DrawFrameView(colour, view), {cv::IMWRITE_JPEG_QUALITY, 90});
  } catch (const cv::Exception& e) {
    throw Error(fmt::format("{}: cannot write: {}", file.string(), e.what()));
  }
  if (!ok) throw Error(fmt::format("{}: cannot write", file.string()));
}

}  // namespace dlslam::app
