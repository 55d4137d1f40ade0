#include "dlslam/map/map_file.h"

#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <cmath>
#include <cstring>

#include "dlslam/tracking/tracker.h"
#include "dlslam/util/check.h"
#include "dlslam/util/crc32.h"
#include "tests/support/landmark_scene.h"
#include "tests/support/test_data.h"

namespace dlslam {
namespace {

using ::testing::HasSubstr;

// A map as tracking makes it: 60 frames along a smooth path through a room
// of landmarks (keyframes, depth points, covisibility, spanning tree), and
// a loop edge and a culled keyframe record as loop closing and local
// mapping would add them.
class MapFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto scene = testing::LandmarkScene::Room(4000, 11);
    camera_ = scene.camera;
    pyramid_ = scene.pyramid;
    Tracker tracker(TrackerOptions(), &map_);
    for (int i = 0; i < 60; ++i) {
      const double t = i / 30.0;
      const SE3d pose = SE3d(SO3d::Exp(Eigen::Vector3d(0.0, 0.3 * std::sin(t), 0.0)),
                             Eigen::Vector3d(0.3 * std::sin(0.7 * t), 0.0, 0.2 * t)).Inverse();
      ASSERT_EQ(tracker.Track(scene.MakeFrame(pose, t, 100 + i)).state, TrackingState::kOk);
    }
    ASSERT_GE(map_.NumKeyFrames(), 3u);
    const std::vector<KeyFramePose> poses = map_.KeyFramePoses();
    for (const KeyFramePose& k : poses) map_.UpdateConnections(k.id);
    map_.AddLoopEdge(poses.front().id, poses.back().id);
  }

  MapFileHeader Header() const { return {camera_, pyramid_}; }
  std::string Bytes() const { return SerializeMap(map_.Export(), Header()); }
  // Re-seals the checksum after editing the payload, so that the parser
  // behind it is reached.
  static void Reseal(std::string* bytes) {
    const std::uint32_t crc = Crc32(std::string_view(*bytes).substr(0, bytes->size() - 4));
    std::memcpy(bytes->data() + bytes->size() - 4, &crc, 4);
  }
  static std::string ParseError(const std::string& bytes) {
    Map map;
    try {
      ParseMap(bytes, "room.dlmap", &map);
    } catch (const InputError& e) {
      EXPECT_EQ(map.NumKeyFrames(), 0u);
      return e.what();
    }
    ADD_FAILURE() << "parsed";
    return "";
  }

  CameraIntrinsics camera_;
  ScalePyramid pyramid_;
  Map map_;
};

TEST_F(MapFileTest, LoadThenSaveGivesTheSameBytesAndTheSameMap) {
  const std::string bytes = Bytes();
  Map loaded;
  const MapFileHeader header = ParseMap(bytes, "room.dlmap", &loaded);
  EXPECT_EQ(header.camera.fx, camera_.fx);
  EXPECT_EQ(header.camera.name, camera_.name);
  EXPECT_EQ(header.pyramid.levels, pyramid_.levels);
  EXPECT_EQ(SerializeMap(loaded.Export(), header), bytes);
  EXPECT_EQ(loaded.NumKeyFrames(), map_.NumKeyFrames());
  EXPECT_EQ(loaded.NumMapPoints(), map_.NumMapPoints());
  EXPECT_EQ(loaded.PointPositions().size(), map_.NumMapPoints());
  // The frames behave as the originals: same keypoints found in an area.
  const std::vector<KeyFramePose> poses = map_.KeyFramePoses();
  const auto a = map_.GetKeyFrame(poses.back().id);
  const auto b = loaded.GetKeyFrame(poses.back().id);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->frame->FeaturesInArea(320, 240, 40), b->frame->FeaturesInArea(320, 240, 40));
  EXPECT_EQ(a->points, b->points);
  EXPECT_EQ(a->cam_from_world.translation(), b->cam_from_world.translation());
  // A tracker continues on the loaded map's local map as on the original.
  EXPECT_EQ(loaded.GetLocalMap(a->points).points.size(), map_.GetLocalMap(a->points).points.size());
}

// The first keyframes of maps not merged yet (a new map after a loss) stay
// anchors after a load; a version 1 file (before anchors) still loads.
TEST_F(MapFileTest, AnchorsSurviveAndVersionOneStillLoads) {
  const std::vector<KeyFramePose> poses = map_.KeyFramePoses();
  const KeyFrameId anchor = poses[poses.size() / 2].id;
  ASSERT_NE(anchor, 0u);
  map_.SetAnchor(anchor);
  const std::string bytes = Bytes();
  Map loaded;
  ParseMap(bytes, "room.dlmap", &loaded);
  EXPECT_TRUE(loaded.IsAnchor(anchor));
  EXPECT_EQ(loaded.MapOrigin(poses.back().id), anchor);
  EXPECT_EQ(loaded.Export().anchors, std::vector<KeyFrameId>{anchor});

  // Version 1: the same payload without the anchor list (its count and one id).
  std::string v1 = bytes.substr(0, bytes.size() - 4 - 16) + std::string(4, '\0');
  const std::uint32_t one = 1;
  std::memcpy(v1.data() + 8, &one, sizeof one);
  std::uint64_t payload = 0;
  std::memcpy(&payload, v1.data() + 16, sizeof payload);
  payload -= 16;
  std::memcpy(v1.data() + 16, &payload, sizeof payload);
  Reseal(&v1);
  Map old;
  ParseMap(v1, "old.dlmap", &old);
  EXPECT_EQ(old.NumKeyFrames(), map_.NumKeyFrames());
  EXPECT_FALSE(old.IsAnchor(anchor));

  // An anchor that is no keyframe is a defect.
  MapContents contents = map_.Export();
  contents.anchors = {424242};
  EXPECT_THAT(ParseError(SerializeMap(contents, Header())), HasSubstr("anchor 424242 is not a keyframe"));
}

TEST_F(MapFileTest, SaveAndLoadAFile) {
  const std::filesystem::path file = testing::MakeTempDir("map_file") / "room.dlmap";
  SaveMap(map_, Header(), file);
  Map loaded;
  LoadMap(file, &loaded);
  EXPECT_EQ(loaded.NumMapPoints(), map_.NumMapPoints());
  EXPECT_THAT(ParseError(std::string()), HasSubstr("not a DLSLAM map"));
  Map other;
  EXPECT_THROW(LoadMap(file.parent_path() / "missing.dlmap", &other), InputError);
}

TEST_F(MapFileTest, EveryDefectIsAnInputErrorWithTheOffset) {
  const std::string good = Bytes();
  EXPECT_THAT(ParseError("GIF89a" + good), HasSubstr("not a DLSLAM map (offset 0"));
  std::string version = good;
  version[8] = 7;
  EXPECT_THAT(ParseError(version), HasSubstr("unsupported map version 7 (offset 8)"));
  EXPECT_THAT(ParseError(good.substr(0, good.size() / 2)), HasSubstr("truncated"));
  EXPECT_THAT(ParseError(good + "x"), HasSubstr("after the checksum"));
  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x10;
  EXPECT_THAT(ParseError(flipped), HasSubstr("checksum mismatch"));
  // Past the checksum: a keypoint count far beyond the file.
  std::string count = good;
  const std::size_t camera_bytes = 4 + camera_.name.size() + 8 + 11 * 8 + 4 + 8;
  const std::size_t first_keyframe = 24 + camera_bytes + 16 + 8;
  const std::size_t keypoint_count = first_keyframe + 8 + 8 + 56 + 8;
  const std::uint64_t huge = 1ull << 40;
  std::memcpy(count.data() + keypoint_count, &huge, 8);
  Reseal(&count);
  EXPECT_THAT(ParseError(count), HasSubstr(fmt::format("keypoint count {} at offset {}", huge, keypoint_count)));
  // A pose that is not a rotation.
  std::string pose = good;
  const double two = 2.0;
  std::memcpy(pose.data() + first_keyframe + 16, &two, 8);
  Reseal(&pose);
  EXPECT_THAT(ParseError(pose), HasSubstr(fmt::format("keyframe pose at offset {} is not a pose", first_keyframe + 16)));
}

TEST_F(MapFileTest, AMapThatIsNotOneIsRefused) {
  MapContents contents = map_.Export();
  // A point observed by a keyframe that does not exist.
  contents.points.front().observations[999999] = 0;
  EXPECT_THAT(ParseError(SerializeMap(contents, Header())), HasSubstr("unknown keyframe 999999"));
  contents = map_.Export();
  contents.keyframes.back().parent = 424242;
  EXPECT_THAT(ParseError(SerializeMap(contents, Header())), HasSubstr("unknown parent 424242"));
  contents = map_.Export();
  contents.points.back().position.x() = std::nan("");
  EXPECT_THAT(ParseError(SerializeMap(contents, Header())), HasSubstr("non-finite"));
  contents = map_.Export();
  contents.next_point_id = 0;
  EXPECT_THAT(ParseError(SerializeMap(contents, Header())), HasSubstr("is not below the next id"));
  // Import into a map that is not empty is a programming error.
  MapContents again = map_.Export();
  EXPECT_THROW(map_.Import(std::move(again)), Error);
}

}  // namespace
}  // namespace dlslam
