#include "dlslam/data/trajectory.h"

#include <gtest/gtest.h>

namespace dlslam {
namespace {

TEST(Trajectory, PoseRoundTripsThroughSe3) {
  Eigen::Matrix<double, 6, 1> xi;
  xi << 0.1, -0.2, 0.3, 0.4, 0.5, -0.6;
  const SE3d pose = SE3d::Exp(xi);
  const StampedPose sp(12.5, pose);
  EXPECT_EQ(sp.timestamp, 12.5);
  EXPECT_LT((sp.world_from_cam().matrix() - pose.matrix()).norm(), 1e-15);
}

TEST(Trajectory, IncreasingTimestamps) {
  Trajectory t(3);
  t[0].timestamp = 1;
  t[1].timestamp = 2;
  t[2].timestamp = 3;
  EXPECT_TRUE(HasIncreasingTimestamps(t));
  t[2].timestamp = 2;
  EXPECT_FALSE(HasIncreasingTimestamps(t));
  EXPECT_TRUE(HasIncreasingTimestamps({}));
}

}  // namespace
}  // namespace dlslam
