#include "dlslam/match/projection_matcher.h"

#include <gtest/gtest.h>

#include "dlslam/map/map.h"
#include "dlslam/util/check.h"
#include "tests/support/landmark_scene.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

// Points of keyframe 0 searched in a second view: matches must be right.
class ProjectionMatcherTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = testing::LandmarkScene::Room(3000, 5);
    Vector6d xi;
    xi << 0.15, -0.05, 0.1, 0.03, -0.04, 0.02;
    pose1_ = SE3d::Exp(xi);
    auto f0 = scene_.MakeFrame(SE3d(), 0, 1, 0.5, 8, &lm0_);
    frame1_ = scene_.MakeFrame(pose1_, 1, 2, 0.5, 8, &lm1_);
    const KeyFrameId k0 = map_.AddKeyFrame(f0, SE3d());
    for (std::size_t i = 0; i < lm0_.size(); ++i) {
      landmark_of_point_[map_.AddMapPoint(scene_.points[lm0_[i]], k0, static_cast<int>(i))] = lm0_[i];
    }
    std::vector<MapPointId> all;
    for (const auto& [id, lm] : landmark_of_point_) all.push_back(id);
    points_ = map_.GetPoints(all);
  }
  // Fraction of matches that pair a keypoint with its own landmark.
  double Precision(const std::vector<MapPointId>& matches, int* count) const {
    int right = 0;
    *count = 0;
    for (std::size_t i = 0; i < matches.size(); ++i) {
      if (matches[i] == kNoId) continue;
      ++*count;
      right += landmark_of_point_.at(matches[i]) == lm1_[i];
    }
    return *count ? static_cast<double>(right) / *count : 0.0;
  }

  testing::LandmarkScene scene_;
  Map map_;
  SE3d pose1_;
  std::shared_ptr<Frame> frame1_;
  std::vector<int> lm0_, lm1_;
  std::map<MapPointId, int> landmark_of_point_;
  std::vector<MapPointView> points_;
};

TEST_F(ProjectionMatcherTest, MatchesAroundAGoodPoseGuess) {
  Vector6d small;
  small << 0.01, 0.0, -0.01, 0.002, 0.0, 0.001;
  std::vector<MapPointId> matches;
  const auto stats = SearchByProjection(*frame1_, SE3d::Exp(small) * pose1_, points_, {}, &matches);
  int count = 0;
  EXPECT_GT(Precision(matches, &count), 0.99);
  EXPECT_GT(count, 0.8 * stats.projected);
  EXPECT_EQ(count, stats.matched);
}

TEST_F(ProjectionMatcherTest, TakenKeypointsAreSkipped) {
  std::vector<MapPointId> matches;
  SearchByProjection(*frame1_, pose1_, points_, {}, &matches);
  // A second search does not move keypoints that already hold a point.
  std::vector<MapPointId> again = matches;
  SearchByProjection(*frame1_, pose1_, points_, {}, &again);
  EXPECT_EQ(again, matches);
}

TEST_F(ProjectionMatcherTest, MatchToKeyFrameWithoutPose) {
  const auto kf = map_.GetKeyFrame(0);
  ASSERT_TRUE(kf.has_value());
  const std::vector<MapPointId> matches = MatchToKeyFrame(*frame1_, *kf->frame, kf->points);
  int count = 0;
  EXPECT_GT(Precision(matches, &count), 0.99);
  EXPECT_GT(count, 100);
}

TEST(ProjectionMatchOptions, Check) {
  ProjectionMatchOptions o;
  o.ratio = 1.5;
  EXPECT_THROW(o.Check(), Error);
}

}  // namespace
}  // namespace dlslam
