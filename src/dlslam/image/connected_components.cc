#include "dlslam/image/connected_components.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "dlslam/util/check.h"

namespace dlslam::image {
namespace {

struct Run {
  int row, begin, end;  // set pixels [begin, end) of a row
};

int FindRoot(std::vector<int>& parent, int i) {
  int root = i;
  while (parent[static_cast<std::size_t>(root)] != root) root = parent[static_cast<std::size_t>(root)];
  while (parent[static_cast<std::size_t>(i)] != root) {  // path compression
    const int next = parent[static_cast<std::size_t>(i)];
    parent[static_cast<std::size_t>(i)] = root;
    i = next;
  }
  return root;
}

void Unite(std::vector<int>& parent, int a, int b) {
  a = FindRoot(parent, a);
  b = FindRoot(parent, b);
  // The smaller index stays the root, so labels follow the first run.
  if (a < b) parent[static_cast<std::size_t>(b)] = a;
  if (b < a) parent[static_cast<std::size_t>(a)] = b;
}

// Appends the runs of set pixels of one row; skips zero stretches 8 bytes at a time.
void FindRuns(const std::uint8_t* row, int width, int y, std::vector<Run>& runs) {
  int x = 0;
  while (x < width) {
    while (x + 8 <= width) {
      std::uint64_t word;
      std::memcpy(&word, row + x, 8);
      if (word != 0) break;
      x += 8;
    }
    while (x < width && row[x] == 0) ++x;
    if (x >= width) break;
    const int begin = x;
    while (x < width && row[x] != 0) ++x;
    runs.push_back({y, begin, x});
  }
}

}  // namespace

int LabelComponents(const cv::Mat& mask, cv::Mat& labels, std::vector<int>* areas) {
  DLSLAM_CHECK(mask.type() == CV_8UC1, "LabelComponents: the mask must be CV_8UC1, got {}",
               cv::typeToString(mask.type()));
  std::vector<Run> runs;
  std::vector<int> parent;
  std::size_t previous_begin = 0, previous_end = 0;  // the runs of the row above
  for (int y = 0; y < mask.rows; ++y) {
    const std::size_t row_begin = runs.size();
    FindRuns(mask.ptr<std::uint8_t>(y), mask.cols, y, runs);
    std::size_t p = previous_begin;
    for (std::size_t r = row_begin; r < runs.size(); ++r) {
      parent.push_back(static_cast<int>(r));
      // 8-connected: a run above touches when it overlaps [begin - 1, end].
      while (p < previous_end && runs[p].end < runs[r].begin) ++p;
      for (std::size_t q = p; q < previous_end && runs[q].begin <= runs[r].end; ++q) {
        Unite(parent, static_cast<int>(q), static_cast<int>(r));
      }
      // The last run above that touched may touch the next run too: p stays.
    }
    previous_begin = row_begin;
    previous_end = runs.size();
  }
  // Roots come before their runs, so one pass numbers the components.
  std::vector<int> label_of(runs.size(), 0);
  int count = 1;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const int root = FindRoot(parent, static_cast<int>(r));
    label_of[r] = root == static_cast<int>(r) ? count++ : label_of[static_cast<std::size_t>(root)];
  }
  labels.create(mask.size(), CV_32SC1);
  labels.setTo(cv::Scalar(0));
  if (areas != nullptr) areas->assign(static_cast<std::size_t>(count), 0);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    int* row = labels.ptr<int>(runs[r].row);
    std::fill(row + runs[r].begin, row + runs[r].end, label_of[r]);
    if (areas != nullptr) (*areas)[static_cast<std::size_t>(label_of[r])] += runs[r].end - runs[r].begin;
  }
  if (areas != nullptr) {
    int set = 0;
    for (std::size_t i = 1; i < areas->size(); ++i) set += (*areas)[i];
    (*areas)[0] = static_cast<int>(mask.total()) - set;
  }
  return count;
}

}  // namespace dlslam::image
