#include "dlslam/datasets/catalogue.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "dlslam/util/check.h"

namespace dlslam::datasets {
namespace {

using ::testing::HasSubstr;

TEST(Catalogue, UrlsFollowThePublishersLayout) {
  // Reference URLs as published on the TUM and Bonn download pages.
  EXPECT_EQ(ArchiveUrl(FindSequence("rgbd_dataset_freiburg3_walking_xyz"), ""),
            "https://cvg.cit.tum.de/rgbd/dataset/freiburg3/rgbd_dataset_freiburg3_walking_xyz.tgz");
  EXPECT_EQ(ArchiveUrl(FindSequence("rgbd_dataset_freiburg1_xyz"), ""),
            "https://cvg.cit.tum.de/rgbd/dataset/freiburg1/rgbd_dataset_freiburg1_xyz.tgz");
  EXPECT_EQ(ArchiveUrl(FindSequence("rgbd_bonn_crowd"), ""),
            "https://www.ipb.uni-bonn.de/html/projects/rgbd_dynamic2019/rgbd_bonn_crowd.zip");
  EXPECT_EQ(ArchiveUrl(FindSequence("rgbd_bonn_crowd"), "http://mirror.local/bonn/"),
            "http://mirror.local/bonn/rgbd_bonn_crowd.zip");
  EXPECT_EQ(ArchiveFileName(FindSequence("fr2/desk_with_person")), "rgbd_dataset_freiburg2_desk_with_person.tgz");
}

TEST(Catalogue, HoldsEveryCategoryAndUniqueNames) {
  std::set<std::string> names;
  std::map<std::string, int> per_category;
  int bonn = 0;
  for (const SequenceInfo& info : Catalogue()) {
    EXPECT_TRUE(names.insert(info.name).second) << "duplicate " << info.name;
    if (info.collection == Collection::kBonn) {
      ++bonn;
      EXPECT_TRUE(info.name.starts_with("rgbd_bonn_")) << info.name;
    } else {
      ++per_category[info.category];
      EXPECT_TRUE(info.name.starts_with("rgbd_dataset_freiburg")) << info.name;
      EXPECT_EQ(info.archive_path, "freiburg" + info.name.substr(21, 1) + "/" + info.name + ".tgz");
    }
    // Sizes and checksums are only filled from measurements; none are invented.
    EXPECT_TRUE(info.sha256.empty() || info.sha256.size() == 64) << info.name;
    EXPECT_TRUE(info.md5.empty() || info.md5.size() == 32) << info.name;
  }
  // Counts of the TUM download page's groups and the Bonn page (24 dynamic + 2 static).
  EXPECT_EQ(per_category["testing"], 4);
  EXPECT_EQ(per_category["handheld"], 11);
  EXPECT_EQ(per_category["robot"], 4);
  EXPECT_EQ(per_category["structure_texture"], 8);
  EXPECT_EQ(per_category["dynamic"], 9);
  EXPECT_EQ(per_category["reconstruction"], 11);
  EXPECT_EQ(bonn, 26);
  for (const char* name : {"fr3/walking_halfsphere", "fr3/sitting_static", "fr1/room_validation",
                           "fr3/calibration_rgb_depth", "bonn/balloon_tracking2", "bonn/static_close_far",
                           "bonn/kidnapping_box", "bonn/placing_nonobstructing_box3"}) {
    EXPECT_NE(LookupSequence(name), nullptr) << name;
  }
}

TEST(Catalogue, AcceptsFullAndShortNames) {
  const SequenceInfo* walking = LookupSequence("rgbd_dataset_freiburg3_walking_xyz");
  ASSERT_NE(walking, nullptr);
  for (const char* alias : {"fr3/walking_xyz", "freiburg3_walking_xyz", "freiburg3/walking_xyz", "fr3_walking_xyz",
                            "FR3/Walking_XYZ", " fr3/walking_xyz/ ", "rgbd_dataset_freiburg3_walking_xyz.tgz"}) {
    EXPECT_EQ(LookupSequence(alias), walking) << alias;
  }
  const SequenceInfo* crowd = LookupSequence("rgbd_bonn_crowd");
  ASSERT_NE(crowd, nullptr);
  for (const char* alias : {"bonn/crowd", "bonn_crowd", "Bonn/Crowd", "rgbd_bonn_crowd.zip"}) {
    EXPECT_EQ(LookupSequence(alias), crowd) << alias;
  }
  EXPECT_EQ(ShortName(*walking), "fr3/walking_xyz");
  EXPECT_EQ(ShortName(*crowd), "bonn/crowd");
  // Short names round-trip for every entry.
  for (const SequenceInfo& info : Catalogue()) EXPECT_EQ(LookupSequence(ShortName(info)), &info) << info.name;
}

TEST(Catalogue, UnknownNameListsCloseMatches) {
  EXPECT_EQ(LookupSequence("fr3/walking_xzy"), nullptr);
  EXPECT_EQ(LookupSequence("fr4/walking_xyz"), nullptr);
  EXPECT_EQ(LookupSequence(""), nullptr);
  try {
    FindSequence("fr3/walking_xzy");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown sequence 'fr3/walking_xzy'"));
    EXPECT_THAT(e.what(), HasSubstr("fr3/walking_xyz"));
  }
  const auto crowd = CloseMatches("bonn/crowd4");
  ASSERT_FALSE(crowd.empty());
  EXPECT_THAT(crowd, ::testing::Contains("bonn/crowd"));
  // A substring finds its family.
  EXPECT_THAT(CloseMatches("halfsphere"), ::testing::Contains("fr3/walking_halfsphere"));
  EXPECT_LE(CloseMatches("halfsphere", 3).size(), 3u);
  try {
    FindSequence("qqqqqqqqqqqqqqqqqqqq");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("dlslam dataset list"));
    EXPECT_THAT(e.what(), ::testing::Not(HasSubstr("did you mean")));
  }
}

TEST(Catalogue, JsonListsEveryEntry) {
  const auto json = nlohmann::json::parse(CatalogueJson());
  ASSERT_TRUE(json.is_array());
  ASSERT_EQ(json.size(), Catalogue().size());
  const auto& first = json.front();
  EXPECT_EQ(first.at("name"), "rgbd_dataset_freiburg1_xyz");
  EXPECT_EQ(first.at("short_name"), "fr1/xyz");
  EXPECT_EQ(first.at("collection"), "tum");
  EXPECT_EQ(first.at("url"), "https://cvg.cit.tum.de/rgbd/dataset/freiburg1/rgbd_dataset_freiburg1_xyz.tgz");
  EXPECT_TRUE(first.at("size_bytes").is_null());
  EXPECT_TRUE(first.at("sha256").is_null());
  EXPECT_EQ(json.back().at("collection"), "bonn");
}

}  // namespace
}  // namespace dlslam::datasets
