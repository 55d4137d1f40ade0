// End to end: a synthetic sequence written in the TUM layout, read back
// through the same reader as real TUM data, tracked and mapped by the full
// system, evaluated like the TUM tools.

#include <gtest/gtest.h>

#include <filesystem>

#include "dlslam/eval/ate.h"
#include "dlslam/io/sequence.h"
#include "dlslam/io/sequence_writer.h"
#include "dlslam/synth/sequence.h"
#include "dlslam/system/slam_system.h"
#include "tests/support/test_data.h"

namespace dlslam {
namespace {

class SlamPipelineTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::filesystem::path(testing::MakeTempDir("slam_pipeline"));
    synth::SynthOptions options;
    options.preset = synth::Preset::kStatic;
    options.frames = 60;
    options.seed = 7;
    const synth::SynthSequence sequence(options);
    io::SequenceWriterOptions write;
    write.force = true;
    io::SequenceWriter writer(*dir_, options.camera, write);
    for (int i = 0; i < sequence.size(); ++i) {
      const synth::RenderedFrame f = sequence.Render(i);
      writer.Add(sequence.camera_path()[i].timestamp, f.colour, f.depth, f.mask, f.world_from_cam);
    }
    writer.Finish();
  }
  static void TearDownTestSuite() {
    std::filesystem::remove_all(*dir_);
    delete dir_;
  }

  // Runs the system over the sequence; returns the camera trajectory.
  static Trajectory Run(bool sequential, RunStats* stats = nullptr, SystemOptions options = SystemOptions()) {
    const io::RgbdSequence sequence = io::RgbdSequence::Open(*dir_);
    options.sequential = sequential;
    SlamSystem slam(sequence.camera(), options);
    for (std::size_t i = 0; i < sequence.size(); ++i) {
      const io::RgbdFrame f = sequence.LoadFrame(i);
      slam.TrackRgbd(f.color, f.depth, f.timestamp);
    }
    slam.Shutdown();
    if (stats) *stats = slam.Stats();
    return slam.CameraTrajectory();
  }

  static std::filesystem::path* dir_;
};

std::filesystem::path* SlamPipelineTest::dir_ = nullptr;

TEST_F(SlamPipelineTest, SynthSequenceReadsLikeATumFolder) {
  const io::RgbdSequence sequence = io::RgbdSequence::Open(*dir_);
  EXPECT_EQ(sequence.size(), 60u);
  EXPECT_EQ(sequence.camera().name.empty(), false);
  EXPECT_DOUBLE_EQ(sequence.camera().fx, CameraPreset("freiburg3").fx);
  ASSERT_TRUE(sequence.ground_truth().has_value());
  EXPECT_EQ(sequence.ground_truth()->size(), 60u);
}

TEST_F(SlamPipelineTest, TracksEveryFrameWithSubCentimetreAte) {
  RunStats stats;
  const Trajectory estimate = Run(/*sequential=*/false, &stats);
  EXPECT_EQ(stats.frames_tracked, 60);
  EXPECT_EQ(stats.frames_lost, 0);
  const io::RgbdSequence sequence = io::RgbdSequence::Open(*dir_);
  const eval::AteResult ate = eval::ComputeAte(*sequence.ground_truth(), estimate);
  EXPECT_EQ(ate.pairs, 60u);
  EXPECT_LT(ate.error.rmse, 0.01);
}

TEST_F(SlamPipelineTest, SequentialModeIsReproducibleBitForBit) {
  const Trajectory a = Run(/*sequential=*/true);
  const Trajectory b = Run(/*sequential=*/true);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].timestamp, b[i].timestamp);
    EXPECT_EQ(a[i].translation, b[i].translation);
    EXPECT_EQ(a[i].rotation.coeffs(), b[i].rotation.coeffs());
  }
}

// The modes that remove moving content make a keyframe at least every
// max_frames_between_keyframes_dynamic frames, mode orb every
// max_frames_between_keyframes (here: never for lack of time alone).
TEST_F(SlamPipelineTest, DynamicModesMakeKeyFramesMoreOften) {
  SystemOptions options;
  options.tracker.max_frames_between_keyframes = 1000;
  options.tracker.max_frames_between_keyframes_dynamic = 10;
  RunStats orb, geometry;
  Run(/*sequential=*/true, &orb, options);
  options.dynamic.mode = DynamicMode::kGeometry;
  Run(/*sequential=*/true, &geometry, options);
  EXPECT_EQ(orb.frames_tracked, 60);
  EXPECT_EQ(geometry.frames_tracked, 60);
  EXPECT_GE(geometry.mapping.keyframes_processed, 6);  // the first, then one in 10 frames at most
  EXPECT_GE(geometry.mapping.keyframes_processed, orb.mapping.keyframes_processed + 3);
  RecordProperty("orb_keyframes", orb.mapping.keyframes_processed);
  RecordProperty("geometry_keyframes", geometry.mapping.keyframes_processed);
}

}  // namespace
}  // namespace dlslam
