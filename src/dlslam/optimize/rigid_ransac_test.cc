#include "dlslam/optimize/rigid_ransac.h"

#include <gtest/gtest.h>

#include <random>

#include "dlslam/util/check.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

SE3d TrueTransform() {
  Vector6d xi;
  xi << 0.4, -0.2, 1.1, 0.3, -0.5, 0.2;
  return SE3d::Exp(xi);
}

struct Correspondences {
  std::vector<Eigen::Vector3d> a, b;
  std::vector<double> max_error;
  std::vector<bool> is_outlier;
};

// Points in a 4 m box; the outliers get an unrelated b anywhere in the box.
Correspondences Make(int inliers, int outliers, unsigned seed) {
  Correspondences c;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-2, 2);
  const SE3d b_from_a = TrueTransform();
  for (int i = 0; i < inliers + outliers; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng) + 3);
    c.a.push_back(p);
    const int total = inliers + outliers;
    const bool outlier = (i * outliers) / total != ((i + 1) * outliers) / total;  // exactly `outliers`, spread out
    c.b.push_back(outlier ? Eigen::Vector3d(u(rng), u(rng), u(rng) + 3) : b_from_a * p);
    c.max_error.push_back(0.02);
    c.is_outlier.push_back(outlier);
  }
  return c;
}

RigidRansacOptions Options(int min_inliers) {
  RigidRansacOptions o;
  o.min_inliers = min_inliers;
  return o;
}

TEST(RigidRansac, RecoversTheTransformExactlyWithHalfOutliers) {
  const Correspondences c = Make(60, 60, 1);
  const auto r = EstimateRigidRansac(c.a, c.b, c.max_error, Options(20), 42);
  ASSERT_TRUE(r.has_value());
  EXPECT_LT((r->b_from_a.matrix() - TrueTransform().matrix()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(r->num_inliers, 60);
  for (std::size_t i = 0; i < c.a.size(); ++i) EXPECT_EQ(r->inliers[i], !c.is_outlier[i]) << i;
  // 50 % inliers at 99 % confidence needs ~35 samples, well below the limit.
  EXPECT_LT(r->iterations, 100);
  EXPECT_GE(r->iterations, 1);
}

TEST(RigidRansac, SameSeedSameResult) {
  const Correspondences c = Make(40, 60, 2);
  const auto r1 = EstimateRigidRansac(c.a, c.b, c.max_error, Options(20), 9);
  const auto r2 = EstimateRigidRansac(c.a, c.b, c.max_error, Options(20), 9);
  ASSERT_TRUE(r1 && r2);
  EXPECT_EQ(r1->b_from_a.matrix(), r2->b_from_a.matrix());
  EXPECT_EQ(r1->inliers, r2->inliers);
  EXPECT_EQ(r1->iterations, r2->iterations);
}

TEST(RigidRansac, PureNoiseGivesNothing) {
  Correspondences c = Make(0, 200, 3);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-2, 2);
  for (auto& p : c.b) p = Eigen::Vector3d(u(rng), u(rng), u(rng) + 3);  // all unrelated
  EXPECT_FALSE(EstimateRigidRansac(c.a, c.b, c.max_error, Options(20), 5).has_value());
}

TEST(RigidRansac, TooFewInliersGivesNothing) {
  const Correspondences c = Make(15, 30, 6);
  EXPECT_FALSE(EstimateRigidRansac(c.a, c.b, c.max_error, Options(20), 7).has_value());
  const auto r = EstimateRigidRansac(c.a, c.b, c.max_error, Options(15), 7);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->num_inliers, 15);
}

// 40 exact correspondences and 20 displaced by 5 cm: those with a 10 cm
// threshold are inliers, those with 3 cm are not.
TEST(RigidRansac, PerCorrespondenceThresholdsAreRespected) {
  Correspondences c = Make(60, 0, 8);
  for (int i = 40; i < 60; ++i) {
    c.b[i] += Eigen::Vector3d(0.05, 0, 0);
    c.max_error[i] = i < 50 ? 0.10 : 0.03;
  }
  const auto r = EstimateRigidRansac(c.a, c.b, c.max_error, Options(20), 10);
  ASSERT_TRUE(r.has_value());
  for (int i = 0; i < 60; ++i) EXPECT_EQ(r->inliers[i], i < 50) << i;
  EXPECT_EQ(r->num_inliers, 50);
  // Every flag agrees with the returned transform and the thresholds.
  for (int i = 0; i < 60; ++i) {
    EXPECT_EQ(r->inliers[i], (r->b_from_a * c.a[i] - c.b[i]).norm() <= c.max_error[i]) << i;
  }
  // The refit averages the displaced inliers in: close to the truth, not exact.
  EXPECT_LT((r->b_from_a.translation() - TrueTransform().translation()).norm(), 0.05);
}

TEST(RigidRansac, DegenerateInputGivesNothing) {
  const std::vector<Eigen::Vector3d> same(30, Eigen::Vector3d(1, 2, 3));
  const std::vector<double> errors(30, 0.1);
  EXPECT_FALSE(EstimateRigidRansac(same, same, errors, Options(3), 1).has_value());

  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 30; ++i) line.emplace_back(0.1 * i, 0.2 * i, 1 + 0.05 * i);
  std::vector<Eigen::Vector3d> line_b;
  for (const auto& p : line) line_b.push_back(TrueTransform() * p);
  EXPECT_FALSE(EstimateRigidRansac(line, line_b, errors, Options(3), 1).has_value());

  const Correspondences c = Make(2, 0, 12);
  EXPECT_FALSE(EstimateRigidRansac(c.a, c.b, c.max_error, Options(3), 1).has_value());
  EXPECT_FALSE(EstimateRigidRansac({}, {}, {}, Options(3), 1).has_value());
}

TEST(RigidRansac, BadInputThrows) {
  Correspondences c = Make(30, 0, 13);
  std::vector<Eigen::Vector3d> short_b(c.b.begin(), c.b.end() - 1);
  EXPECT_THROW(EstimateRigidRansac(c.a, short_b, c.max_error, Options(20), 1), Error);
  std::vector<double> short_errors(c.max_error.begin(), c.max_error.end() - 1);
  EXPECT_THROW(EstimateRigidRansac(c.a, c.b, short_errors, Options(20), 1), Error);
  c.max_error[3] = -0.1;
  EXPECT_THROW(EstimateRigidRansac(c.a, c.b, c.max_error, Options(20), 1), Error);
  c.max_error[3] = NAN;
  EXPECT_THROW(EstimateRigidRansac(c.a, c.b, c.max_error, Options(20), 1), Error);
}

TEST(RigidRansac, OptionsAreChecked) {
  RigidRansacOptions o;
  EXPECT_NO_THROW(o.Check());
  o.max_iterations = 0;
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.confidence = 1.0;
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.min_inliers = 2;
  EXPECT_THROW(o.Check(), Error);
}

}  // namespace
}  // namespace dlslam
