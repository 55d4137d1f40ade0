#include "dlslam/image/upsample.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "dlslam/util/check.h"

namespace dlslam::image {
namespace {

// One output row from one grid row. Factors 2 and 4 write a cell as one
// 16- or 32-bit word (the byte times 0x0101...), which the compiler turns
// into vector shuffles; other factors fill per cell.
void ExpandRow(const std::uint8_t* cells, int factor, int width, std::uint8_t* row) {
  const int whole = width / factor;  // cells that fit entirely
  if (factor == 2) {
    for (int c = 0; c < whole; ++c) {
      const auto v = static_cast<std::uint16_t>(cells[c] * 0x0101u);
      std::memcpy(row + 2 * c, &v, 2);
    }
  } else if (factor == 4) {
    for (int c = 0; c < whole; ++c) {
      const std::uint32_t v = cells[c] * 0x01010101u;
      std::memcpy(row + 4 * c, &v, 4);
    }
  } else {
    for (int c = 0; c < whole; ++c) std::memset(row + c * factor, cells[c], static_cast<std::size_t>(factor));
  }
  const int tail = width - whole * factor;  // a cell cut by the crop
  if (tail > 0) std::memset(row + whole * factor, cells[whole], static_cast<std::size_t>(tail));
}

}  // namespace

void UpsampleNearest(const cv::Mat& grid, int factor, cv::Size size, cv::Mat& out) {
  DLSLAM_CHECK(grid.type() == CV_8UC1, "UpsampleNearest: the grid must be CV_8UC1, got {}",
               cv::typeToString(grid.type()));
  DLSLAM_CHECK(factor >= 1, "UpsampleNearest: factor {} must be >= 1", factor);
  DLSLAM_CHECK(size.width >= 0 && size.height >= 0 && size.width <= grid.cols * factor &&
                   size.height <= grid.rows * factor,
               "UpsampleNearest: {}x{} is not within the {}x{} grid times {}", size.width, size.height, grid.cols,
               grid.rows, factor);
  DLSLAM_CHECK(out.data != grid.data || grid.empty(), "UpsampleNearest: the output cannot be the grid itself");
  out.create(size, CV_8UC1);
  const auto width = static_cast<std::size_t>(size.width);
  for (int y = 0; y < size.height; ++y) {
    std::uint8_t* row = out.ptr<std::uint8_t>(y);
    if (y % factor != 0) {  // the row above comes from the same grid row
      std::memcpy(row, out.ptr<std::uint8_t>(y - 1), width);
    } else {
      ExpandRow(grid.ptr<std::uint8_t>(y / factor), factor, size.width, row);
    }
  }
}

cv::Mat UpsampleNearest(const cv::Mat& grid, int factor, cv::Size size) {
  cv::Mat out;
  UpsampleNearest(grid, factor, size, out);
  return out;
}

}  // namespace dlslam::image
