#pragma once
// Reading the colour and depth images of an RGB-D frame. Every error names
// the image and the list file:line that referenced it:
//   "/seq/depth.txt:57: depth image '/seq/depth/1.2.png': 8-bit image, expected 16-bit"

#include <filesystem>
#include <opencv2/core.hpp>

namespace dlslam::io {

// Where an image was referenced (a line of rgb.txt, depth.txt or an
// association file). line 0 = no list.
struct ImageSource {
  std::filesystem::path image;      // path of the image file as opened
  std::filesystem::path list_file;  // the list that named it
  int line = 0;
};

// Colour image as CV_8UC3 BGR: 8-bit 3-channel PNG or JPEG; 4 channels drop
// alpha; 8-bit grayscale is replicated into three channels (documented
// conversion: some cameras record mono). Throws InputError for a missing,
// empty or undecodable file, 16-bit colour, or a size other than
// width x height (skipped when width or height is 0).
cv::Mat ReadColorImage(const ImageSource& source, int width, int height);

// Depth image as CV_32FC1 metres: a 16-bit single-channel PNG divided by
// depth_factor (raw units per metre); raw 0 stays 0 (no measurement).
// Throws InputError for a missing, empty (0 bytes) or undecodable file, an
// 8-bit or multi-channel image, or a size other than width x height.
cv::Mat ReadDepthImage(const ImageSource& source, double depth_factor, int width, int height);

// Mask image as CV_8UC1 (a label per pixel, e.g. `dlslam synth`'s ground
// truth or a segmentation): an 8-bit single-channel PNG. Throws InputError
// for the file errors above, a 16-bit or multi-channel image, or a size other
// than width x height.
cv::Mat ReadMaskImage(const ImageSource& source, int width, int height);

// The size of an image file (decodes it). Same file errors as above.
cv::Size ReadImageSize(const ImageSource& source);

// Writes an image; the format follows the extension (PNG for masks and depth).
// Throws InputError naming the file when OpenCV cannot write it.
void WriteImage(const std::filesystem::path& path, const cv::Mat& image);

}  // namespace dlslam::io
