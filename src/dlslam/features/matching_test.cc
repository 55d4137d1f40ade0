#include "dlslam/features/matching.h"

#include <gtest/gtest.h>

#include <random>

#include "dlslam/util/check.h"

namespace dlslam::features {
namespace {

cv::Mat RandomDescriptors(int n, unsigned seed) {
  cv::Mat d(n, kDescriptorBytes, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(d, cv::RNG::UNIFORM, 0, 256);
  return d;
}

void FlipBits(cv::Mat row, int n_bits, std::mt19937& rng) {
  std::uniform_int_distribution<int> bit(0, 8 * kDescriptorBytes - 1);
  for (int i = 0; i < n_bits; ++i) {
    const int b = bit(rng);
    row.at<uchar>(0, b / 8) ^= static_cast<uchar>(1 << (b % 8));
  }
}

TEST(HammingDistanceTest, AgreesWithOpenCv) {
  const cv::Mat a = RandomDescriptors(50, 1), b = RandomDescriptors(50, 2);
  for (int i = 0; i < a.rows; ++i) {
    EXPECT_EQ(HammingDistance(a.ptr<uchar>(i), b.ptr<uchar>(i)),
              cv::norm(a.row(i), b.row(i), cv::NORM_HAMMING));
  }
  EXPECT_EQ(HammingDistance(a.ptr<uchar>(3), a.ptr<uchar>(3)), 0);
  cv::Mat zeros = cv::Mat::zeros(1, kDescriptorBytes, CV_8UC1), ones = zeros.clone();
  ones.setTo(255);
  EXPECT_EQ(HammingDistance(zeros.ptr<uchar>(0), ones.ptr<uchar>(0)), 256);
}

TEST(MatchBruteForceTest, FindsNoisyCopiesAmongDistractors) {
  const cv::Mat query = RandomDescriptors(40, 3);
  cv::Mat train = RandomDescriptors(100, 4);  // rows 0..59 distractors
  std::mt19937 rng(5);
  for (int i = 0; i < 40; ++i) {
    query.row(i).copyTo(train.row(60 + (i * 7) % 40));
    FlipBits(train.row(60 + (i * 7) % 40), 20, rng);
  }
  const std::vector<cv::DMatch> matches = MatchBruteForce(query, train);
  ASSERT_EQ(matches.size(), 40u);
  for (const cv::DMatch& m : matches) {
    EXPECT_EQ(m.trainIdx, 60 + (m.queryIdx * 7) % 40);
    EXPECT_LE(m.distance, 20.0f);
  }
  MatchOptions strict;
  strict.max_distance = 5;
  EXPECT_TRUE(MatchBruteForce(query, train, strict).empty());
}

TEST(MatchBruteForceTest, RatioAndMutualTestsRejectAmbiguousMatches) {
  cv::Mat query = RandomDescriptors(2, 6);
  cv::Mat train(3, kDescriptorBytes, CV_8UC1);
  query.row(0).copyTo(train.row(0));
  query.row(0).copyTo(train.row(1));  // two equally good candidates for query 0
  query.row(1).copyTo(train.row(2));
  std::vector<cv::DMatch> matches = MatchBruteForce(query, train);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].queryIdx, 1);

  MatchOptions no_ratio;
  no_ratio.ratio = 1.0;
  no_ratio.mutual = false;
  EXPECT_EQ(MatchBruteForce(query, train, no_ratio).size(), 2u);

  // Both queries nearest to train 0; only the nearer one survives the mutual test.
  cv::Mat near_query(2, kDescriptorBytes, CV_8UC1), one_train = RandomDescriptors(1, 7);
  one_train.copyTo(near_query.row(0));
  one_train.copyTo(near_query.row(1));
  std::mt19937 rng(8);
  FlipBits(near_query.row(1), 10, rng);
  MatchOptions mutual_only;
  mutual_only.ratio = 1.0;
  matches = MatchBruteForce(near_query, one_train, mutual_only);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].queryIdx, 0);
}

TEST(MatchBruteForceTest, RejectsBadInput) {
  const cv::Mat good = RandomDescriptors(3, 9);
  EXPECT_TRUE(MatchBruteForce(cv::Mat(), good).empty());
  EXPECT_THROW(MatchBruteForce(cv::Mat(3, 16, CV_8UC1), good), Error);
  EXPECT_THROW(MatchBruteForce(good, cv::Mat(3, kDescriptorBytes, CV_32FC1)), Error);
  MatchOptions bad;
  bad.ratio = 0.0;
  EXPECT_THROW(MatchBruteForce(good, good, bad), Error);
  bad = {};
  bad.max_distance = 300;
  EXPECT_THROW(MatchBruteForce(good, good, bad), Error);
}

}  // namespace
}  // namespace dlslam::features
