// Bad frames in a run (issue 3, "Bad input and robustness"): frames without
// depth, black frames, an image listed but missing, a start in motion blur.
// A clean synthetic sequence is written once; each test writes a spoiled
// copy, runs it the way `dlslam run` does (TryLoadFrame, MarkLost on an
// unreadable frame), and checks: no crash, the spoiled frames reported lost
// or waiting, tracking back after them, the counts adding up, a well-formed
// trajectory file that reads back, and an accurate trajectory.

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <functional>

#include "dlslam/eval/ate.h"
#include "dlslam/io/sequence.h"
#include "dlslam/io/sequence_writer.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/synth/sequence.h"
#include "dlslam/system/slam_system.h"
#include "tests/support/test_data.h"

namespace dlslam {
namespace {

constexpr int kFrames = 40;

struct RunOutput {
  RunStats stats;
  std::vector<TrackingState> states;  // per frame; kLost for an unreadable one
  Trajectory read_back;               // the trajectory file, read again
  eval::AteResult ate;
};

class SlamRobustnessTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    clean_ = new std::filesystem::path(testing::MakeTempDir("slam_robustness"));
    synth::SynthOptions options;
    options.preset = synth::Preset::kStatic;
    options.frames = kFrames;
    options.seed = 3;
    const synth::SynthSequence sequence(options);
    io::SequenceWriterOptions write;
    write.force = true;
    io::SequenceWriter writer(*clean_, options.camera, write);
    for (int i = 0; i < sequence.size(); ++i) {
      const synth::RenderedFrame f = sequence.Render(i);
      writer.Add(sequence.camera_path()[i].timestamp, f.colour, f.depth, cv::Mat(), f.world_from_cam);
    }
    writer.Finish();
  }
  static void TearDownTestSuite() {
    std::filesystem::remove_all(*clean_);
    delete clean_;
  }
  void TearDown() override {
    if (!spoiled_.empty()) std::filesystem::remove_all(spoiled_);
  }

  // A copy of the clean sequence with `spoil(index, colour, depth)` applied to every frame.
  std::filesystem::path WriteSpoiled(const std::function<void(int, cv::Mat*, cv::Mat*)>& spoil) {
    spoiled_ = testing::MakeTempDir("slam_robustness_spoiled");
    const io::RgbdSequence clean = io::RgbdSequence::Open(*clean_);
    io::SequenceWriterOptions write;
    write.force = true;
    io::SequenceWriter writer(spoiled_, clean.camera(), write);
    const Trajectory& truth = *clean.ground_truth();
    for (std::size_t i = 0; i < clean.size(); ++i) {
      io::RgbdFrame f = clean.LoadFrame(i);
      spoil(static_cast<int>(i), &f.color, &f.depth);
      writer.Add(f.timestamp, f.color, f.depth, cv::Mat(), truth[i].world_from_cam());
    }
    writer.Finish();
    return spoiled_;
  }

  // As `dlslam run --sequential`, then the trajectory file written and read back.
  static RunOutput Run(const std::filesystem::path& dir) {
    const io::RgbdSequence sequence = io::RgbdSequence::Open(dir);
    SystemOptions options;
    options.sequential = true;
    SlamSystem slam(sequence.camera(), options);
    RunOutput out;
    for (std::size_t i = 0; i < sequence.size(); ++i) {
      const io::FrameLoadResult loaded = sequence.TryLoadFrame(i);
      if (!loaded.ok()) {
        slam.MarkLost(sequence.frames()[i].timestamp());
        out.states.push_back(TrackingState::kLost);
        continue;
      }
      out.states.push_back(slam.TrackRgbd(loaded.frame->color, loaded.frame->depth, loaded.frame->timestamp).state);
    }
    slam.Shutdown();
    out.stats = slam.Stats();
    const std::filesystem::path file = dir / "estimate.txt";
    io::WriteTumTrajectory(file, slam.CameraTrajectory());
    out.read_back = io::ReadTumTrajectory(file);
    out.ate = eval::ComputeAte(*sequence.ground_truth(), out.read_back);
    return out;
  }

  // What every spoiled run must satisfy; frames from `resume` on are tracked.
  static void ExpectRecovered(const RunOutput& r, int resume) {
    EXPECT_EQ(r.stats.frames, kFrames);
    EXPECT_EQ(r.stats.frames_tracked + r.stats.frames_coasted + r.stats.frames_lost + r.stats.frames_waiting,
              r.stats.frames);
    for (int i = resume; i < kFrames; ++i) EXPECT_EQ(r.states[i], TrackingState::kOk) << "frame " << i;
    const int posed = r.stats.frames_tracked + r.stats.frames_coasted;
    EXPECT_EQ(static_cast<int>(r.read_back.size()), posed);
    for (std::size_t i = 1; i < r.read_back.size(); ++i) {
      EXPECT_LT(r.read_back[i - 1].timestamp, r.read_back[i].timestamp);
    }
    EXPECT_EQ(static_cast<int>(r.ate.pairs), posed);
    EXPECT_LT(r.ate.error.rmse, 0.02);
  }

  static std::filesystem::path* clean_;
  std::filesystem::path spoiled_;
};

std::filesystem::path* SlamRobustnessTest::clean_ = nullptr;

TEST_F(SlamRobustnessTest, FramesWithoutDepthInTheMiddle) {
  const auto dir = WriteSpoiled([](int i, cv::Mat*, cv::Mat* depth) {
    if (i >= 12 && i < 17) depth->setTo(0.f);  // an all-zero depth PNG
  });
  const RunOutput r = Run(dir);
  // Without depth the frames still track on the map's points (monocular
  // observations in the projection search and the pose optimisation).
  ExpectRecovered(r, 0);
  EXPECT_EQ(r.stats.frames_tracked, kFrames);
}

// A few black frames coast on the motion model (a pose, marked coasted); a
// longer black stretch is lost after max_coasting_frames.
TEST_F(SlamRobustnessTest, BlackFramesCoastThenAreLost) {
  const int coasting = TrackerOptions().max_coasting_frames;
  const int first = 5, last = first + coasting + 3;  // black: [first, last)
  const auto dir = WriteSpoiled([&](int i, cv::Mat* colour, cv::Mat*) {
    if (i >= first && i < last) colour->setTo(cv::Scalar::all(0));
  });
  const RunOutput r = Run(dir);
  for (int i = first; i < first + coasting; ++i) EXPECT_EQ(r.states[i], TrackingState::kCoasting) << "frame " << i;
  for (int i = first + coasting; i < last; ++i) EXPECT_EQ(r.states[i], TrackingState::kLost) << "frame " << i;
  EXPECT_EQ(r.stats.frames_coasted, coasting);
  EXPECT_EQ(r.stats.frames_lost, last - first - coasting);
  ExpectRecovered(r, last);
}

TEST_F(SlamRobustnessTest, ImageMissingInTheMiddle) {
  const auto dir = WriteSpoiled([](int, cv::Mat*, cv::Mat*) {});
  const io::RgbdSequence listed = io::RgbdSequence::Open(dir);
  ASSERT_TRUE(std::filesystem::remove(dir / listed.frames()[22].rgb.path));
  const RunOutput r = Run(dir);
  EXPECT_EQ(r.states[22], TrackingState::kLost);
  EXPECT_EQ(r.stats.frames_lost, 1);
  ExpectRecovered(r, 23);
}

TEST_F(SlamRobustnessTest, StartInMotionBlur) {
  const auto dir = WriteSpoiled([](int i, cv::Mat* colour, cv::Mat*) {
    if (i < 8) cv::blur(*colour, *colour, cv::Size(41, 41));
  });
  const RunOutput r = Run(dir);
  // Blurred frames give too few keypoints with depth to start the map: they
  // wait, and the first sharp frame starts it.
  for (int i = 0; i < 8; ++i) EXPECT_EQ(r.states[i], TrackingState::kNotInitialized) << "frame " << i;
  EXPECT_EQ(r.stats.frames_waiting, 8);
  ExpectRecovered(r, 8);
}

}  // namespace
}  // namespace dlslam
