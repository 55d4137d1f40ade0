#include "dlslam/features/quadtree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace dlslam::features {
namespace {

TEST(DistributeQuadtreeTest, KeepsEverythingWhenThereAreFewCorners) {
  std::vector<FastCorner> corners = {{10, 10, 30}, {50, 60, 20}, {90, 20, 25}};
  DistributeQuadtree(cv::Rect(0, 0, 100, 100), 5, corners);
  EXPECT_EQ(corners.size(), 3u);
  DistributeQuadtree(cv::Rect(0, 0, 100, 100), 0, corners);
  EXPECT_TRUE(corners.empty());
}

TEST(DistributeQuadtreeTest, SpreadsInsteadOfTakingTheStrongest) {
  // 400 strong corners packed in a 40x40 square, 20 weak ones spread out.
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> in_cluster(0, 39), score(50, 100);
  std::vector<FastCorner> corners;
  for (int i = 0; i < 400; ++i) corners.push_back({in_cluster(rng), in_cluster(rng), score(rng)});
  std::vector<cv::Point> sparse;
  for (int i = 0; i < 20; ++i) {
    sparse.emplace_back(60 + (i % 5) * 110, 80 + (i / 5) * 100);
    corners.push_back({sparse.back().x, sparse.back().y, 10});
  }
  const cv::Rect area(0, 0, 640, 480);
  DistributeQuadtree(area, 40, corners);
  EXPECT_EQ(corners.size(), 40u);
  const long sparse_kept = std::count_if(corners.begin(), corners.end(), [&](const FastCorner& c) {
    return std::find(sparse.begin(), sparse.end(), cv::Point(c.x, c.y)) != sparse.end();
  });
  // Taking the 40 highest scores would keep none of them.
  EXPECT_GE(sparse_kept, 18);
}

TEST(DistributeQuadtreeTest, KeepsTheStrongestCornerOfANode) {
  std::vector<FastCorner> corners = {{100, 100, 12}, {101, 101, 40}, {102, 100, 25}};
  DistributeQuadtree(cv::Rect(0, 0, 200, 200), 1, corners);
  ASSERT_EQ(corners.size(), 1u);
  EXPECT_EQ(corners[0].score, 40);
}

TEST(DistributeQuadtreeTest, ReachesTheTargetOnDenseUniformCorners) {
  std::vector<FastCorner> corners;
  for (int y = 0; y < 300; y += 3) {
    for (int x = 0; x < 400; x += 3) corners.push_back({x, y, (x * 7 + y * 13) % 50 + 1});
  }
  const cv::Rect area(0, 0, 400, 300);
  DistributeQuadtree(area, 217, corners);
  EXPECT_EQ(corners.size(), 217u);
  // Every 100x100 block gets its share (12 blocks, ~18 each).
  for (int by = 0; by < 3; ++by) {
    for (int bx = 0; bx < 4; ++bx) {
      const cv::Rect block(bx * 100, by * 100, 100, 100);
      const long n = std::count_if(corners.begin(), corners.end(), [&](const FastCorner& c) {
        return block.contains(cv::Point(c.x, c.y));
      });
      EXPECT_GE(n, 8) << block;
    }
  }
}

TEST(DistributeQuadtreeTest, TerminatesOnDuplicateCorners) {
  std::vector<FastCorner> corners(50, FastCorner{33, 44, 9});
  corners.push_back({200, 100, 5});
  DistributeQuadtree(cv::Rect(0, 0, 300, 200), 10, corners);
  EXPECT_EQ(corners.size(), 2u);
}

}  // namespace
}  // namespace dlslam::features
