// Maps that last: a map made on a synthetic room, saved, loaded and used
// for localization on the same frames (the same accuracy, no keyframe
// added) and for mapping on top of it; a map from another camera refused.

#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <vector>

#include "dlslam/eval/ate.h"
#include "dlslam/synth/sequence.h"
#include "dlslam/system/slam_system.h"
#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam {
namespace {

using ::testing::HasSubstr;

class MapPersistenceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    synth::SynthOptions options;
    options.preset = synth::Preset::kStatic;
    options.frames = 120;
    options.seed = 4;
    const synth::SynthSequence sequence(options);
    camera_ = new CameraIntrinsics(options.camera);
    truth_ = new Trajectory(sequence.camera_path());
    frames_ = new std::vector<synth::RenderedFrame>();
    for (int i = 0; i < sequence.size(); ++i) frames_->push_back(sequence.Render(i));
    file_ = new std::filesystem::path(testing::MakeTempDir("map_persistence") / "room.dlmap");
  }
  static void TearDownTestSuite() {
    delete camera_;
    delete truth_;
    delete frames_;
    delete file_;
  }

  struct Run {
    RunStats stats;
    double ate = 0.0;
  };
  static Run Track(SlamSystem& slam) {
    for (std::size_t i = 0; i < frames_->size(); ++i) {
      slam.TrackRgbd((*frames_)[i].colour, (*frames_)[i].depth, (*truth_)[i].timestamp);
    }
    slam.Shutdown();
    return {slam.Stats(), eval::ComputeAte(*truth_, slam.CameraTrajectory()).error.rmse};
  }
  static SystemOptions Options() {
    SystemOptions options;
    options.sequential = true;
    return options;
  }

  static CameraIntrinsics* camera_;
  static Trajectory* truth_;
  static std::vector<synth::RenderedFrame>* frames_;
  static std::filesystem::path* file_;
};

CameraIntrinsics* MapPersistenceTest::camera_ = nullptr;
Trajectory* MapPersistenceTest::truth_ = nullptr;
std::vector<synth::RenderedFrame>* MapPersistenceTest::frames_ = nullptr;
std::filesystem::path* MapPersistenceTest::file_ = nullptr;

TEST_F(MapPersistenceTest, LocalizesInASavedMapAsWellAsItMapped) {
  SlamSystem mapping(*camera_, Options());
  const Run made = Track(mapping);
  ASSERT_EQ(made.stats.frames_tracked, static_cast<int>(frames_->size()));
  mapping.SaveMap(*file_);

  SystemOptions localize = Options();
  localize.localization_only = true;
  SlamSystem localizing(*camera_, localize);
  localizing.LoadMap(*file_);
  const Run used = Track(localizing);
  // Every frame posed (the first relocalized into the map), no keyframe added.
  EXPECT_EQ(used.stats.frames_tracked, static_cast<int>(frames_->size()));
  EXPECT_EQ(used.stats.relocalizations, 1);
  EXPECT_EQ(used.stats.keyframes, made.stats.keyframes);
  EXPECT_EQ(used.stats.mapping.keyframes_processed, 0);
  // The same accuracy within noise (1 mm: ATE here is ~1 mm).
  EXPECT_LT(used.ate, made.ate + 0.001) << "mapping " << made.ate;

  // Without localization_only, mapping goes on on top of the loaded map.
  SlamSystem extending(*camera_, Options());
  extending.LoadMap(*file_);
  const Run extended = Track(extending);
  EXPECT_EQ(extended.stats.frames_tracked, static_cast<int>(frames_->size()));
  EXPECT_GE(extended.stats.keyframes, made.stats.keyframes);
  EXPECT_LT(extended.ate, made.ate + 0.001);
}

TEST_F(MapPersistenceTest, AMapFromAnotherCameraIsRefused) {
  {
    SlamSystem mapping(*camera_, Options());
    for (int i = 0; i < 10; ++i) mapping.TrackRgbd((*frames_)[i].colour, (*frames_)[i].depth, (*truth_)[i].timestamp);
    mapping.Shutdown();
    mapping.SaveMap(*file_);
  }
  CameraIntrinsics other = *camera_;
  other.fx *= 1.1;
  SlamSystem slam(other, Options());
  try {
    slam.LoadMap(*file_);
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("room.dlmap"));
    EXPECT_THAT(e.what(), HasSubstr("the map was made with camera"));
  }
  // Loading once tracking has begun is a programming error.
  SlamSystem started(*camera_, Options());
  started.TrackRgbd((*frames_)[0].colour, (*frames_)[0].depth, (*truth_)[0].timestamp);
  EXPECT_THROW(started.LoadMap(*file_), Error);
}

}  // namespace
}  // namespace dlslam
