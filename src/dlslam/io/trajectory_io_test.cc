#include "dlslam/io/trajectory_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "dlslam/io/file_util.h"
#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::io {
namespace {

using ::testing::HasSubstr;

class TrajectoryIoTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::MakeTempDir("trajectory_io"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path Write(const std::string& name, const std::string& text) {
    const auto path = dir_ / name;
    std::ofstream(path) << text;
    return path;
  }
  std::string ErrorOf(const std::filesystem::path& path, TrajectoryReadOptions options = {}) {
    try {
      ReadTumTrajectory(path, options);
    } catch (const InputError& e) {
      return e.what();
    }
    return "<no error>";
  }
  static std::string Slurp(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  std::filesystem::path dir_;
};

TEST_F(TrajectoryIoTest, ReadsTumGroundTruthLayout) {
  const auto path = Write("gt.txt",
                          "# ground truth trajectory\n# timestamp tx ty tz qx qy qz qw\n"
                          "1341846313.6378 -0.6885 -3.1192 1.4248 -0.7691 -0.0414 -0.0040 0.6378\n"
                          "1341846313.6478 -0.6869 -3.1189 1.4247 -0.7696 -0.0416 -0.0027 0.6371\n");
  const Trajectory t = ReadTumTrajectory(path);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t[0].timestamp, 1341846313.6378);
  EXPECT_DOUBLE_EQ(t[1].translation.y(), -3.1189);
  // Rounded quaternions (norm off by ~1e-4) are kept exactly as written.
  EXPECT_DOUBLE_EQ(t[0].rotation.x(), -0.7691);
  EXPECT_DOUBLE_EQ(t[0].rotation.w(), 0.6378);
}

TEST_F(TrajectoryIoTest, WriteThenReadIsLossless) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5, 5);
  Trajectory t;
  for (int i = 0; i < 200; ++i) {
    Eigen::Matrix<double, 6, 1> xi;
    for (int k = 0; k < 6; ++k) xi[k] = u(rng);
    t.emplace_back(1341846313.592026 + i / 30.0, SE3d::Exp(xi));
    t.back().timestamp = std::round(t.back().timestamp * 1e6) / 1e6;  // the 6-decimal contract
  }
  const auto path = dir_ / "est.txt";
  WriteTumTrajectory(path, t);
  const Trajectory back = ReadTumTrajectory(path);
  ASSERT_EQ(back.size(), t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(back[i].timestamp, t[i].timestamp);
    EXPECT_EQ(back[i].translation, t[i].translation);
    EXPECT_EQ(back[i].rotation.coeffs(), t[i].rotation.coeffs());
  }
}

TEST_F(TrajectoryIoTest, ReadThenWriteKeepsTheText) {
  const std::string text =
      "# timestamp tx ty tz qx qy qz qw\n"
      "1305031102.175304 1.3405 0.6266 1.6575 0.6574 0.6126 -0.2949 -0.3248\n"
      "1305031102.211214 1.3303 0.6256 1.6464 0.6579 0.6161 -0.2932 -0.3189\n";
  const auto in = Write("in.txt", text);
  const auto out = dir_ / "out.txt";
  WriteTumTrajectory(out, ReadTumTrajectory(in));
  EXPECT_EQ(Slurp(out), text);
}

TEST_F(TrajectoryIoTest, RepeatedTimestampKeepsTheLastPoseAsTheTumTools) {
  const Trajectory t = ReadTumTrajectory(Write("dup.txt", "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n2.0 2 0 0 0 0 0 1\n3.0 3 0 0 0 0 0 1\n"));
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[1].timestamp, 2.0);
  EXPECT_EQ(t[1].translation.x(), 2.0);
  EXPECT_EQ(t[2].translation.x(), 3.0);
}

TEST_F(TrajectoryIoTest, NormalisesFarOffQuaternions) {
  const auto path = Write("q.txt", "1.0 0 0 0 0 0 0 2\n2.0 0 0 0 0 0 0 1\n");
  const Trajectory t = ReadTumTrajectory(path);
  EXPECT_DOUBLE_EQ(t[0].rotation.w(), 1.0);
}

TEST_F(TrajectoryIoTest, BadInputNamesFileAndLine) {
  EXPECT_THAT(ErrorOf(dir_ / "missing.txt"), HasSubstr("missing.txt: file not found"));
  EXPECT_THAT(ErrorOf(Write("short.txt", "# c\n1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 1\n")),
              HasSubstr("short.txt:3: expected 8 values"));
  EXPECT_THAT(ErrorOf(Write("huge.txt", "1.0 0 1e300 0 0 0 0 1\n")),
              HasSubstr("huge.txt:1: ty 1e+300 beyond +-1e+09 m"));
  EXPECT_THAT(ErrorOf(Write("late.txt", "1e300 0 0 0 0 0 0 1\n")), HasSubstr("late.txt:1: timestamp"));
  EXPECT_THAT(ErrorOf(Write("long.txt", "1.0 0 0 " + std::string(100000, '7') + "x 0 0 0 1\n")),
              HasSubstr("(100001 characters) is not a finite number"));
  EXPECT_THAT(ErrorOf(Write("nan.txt", "1.0 0 0 x 0 0 0 1\n")),
              HasSubstr("nan.txt:1: tz 'x' is not a finite number"));
  EXPECT_THAT(ErrorOf(Write("order.txt", "2.0 0 0 0 0 0 0 1\n1.0 0 0 0 0 0 0 1\n")),
              HasSubstr("order.txt:2: timestamp 1.000000 is not after"));
  EXPECT_THAT(ErrorOf(Write("zero.txt", "1.0 0 0 0 0 0 0 0\n")), HasSubstr("zero.txt:1: quaternion is zero"));
  EXPECT_THAT(ErrorOf(Write("empty.txt", "# nothing\n")), HasSubstr("empty.txt: has 0 pose(s)"));
  TrajectoryReadOptions two;
  two.min_poses = 2;
  EXPECT_THAT(ErrorOf(Write("one.txt", "1.0 0 0 0 0 0 0 1\n"), two), HasSubstr("need at least 2"));
}

TEST_F(TrajectoryIoTest, FailedWriteKeepsTheOldFile) {
  const auto path = Write("keep.txt", "precious\n");
  EXPECT_THROW(WriteFileAtomically(path,
                                   [](std::ostream& out) {
                                     out << "half a trajectory";
                                     throw Error("interrupted");
                                   }),
               Error);
  EXPECT_EQ(Slurp(path), "precious\n");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "keep.txt.tmp"));
  EXPECT_THROW(WriteTumTrajectory(dir_ / "no_such_dir" / "x.txt", {}), InputError);
}

}  // namespace
}  // namespace dlslam::io
