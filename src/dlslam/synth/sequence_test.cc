#include "dlslam/synth/sequence.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "dlslam/io/sequence_writer.h"
#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::synth {
namespace {

namespace fs = std::filesystem;

std::string Slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void Write(const SynthSequence& s, const fs::path& dir) {
  io::SequenceWriterOptions w;
  w.description = "test";
  io::SequenceWriter writer(dir, s.options().camera, w);
  for (int i = 0; i < s.size(); ++i) {
    const RenderedFrame f = s.Render(i);
    writer.Add(s.camera_path()[static_cast<std::size_t>(i)].timestamp, f.colour, f.depth, f.mask, f.world_from_cam);
  }
  writer.Finish();
}

TEST(SynthSequence, SameSeedWritesByteIdenticalFiles) {
  const fs::path dir = testing::MakeTempDir("synth_bytes");
  SynthOptions o;
  o.preset = Preset::kSittingStatic;
  o.frames = 3;
  o.seed = 21;
  Write(SynthSequence(o), dir / "a");
  Write(SynthSequence(o), dir / "b");
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "a")) {
    if (!entry.is_regular_file()) continue;
    const fs::path relative = fs::relative(entry.path(), dir / "a");
    EXPECT_EQ(Slurp(entry.path()), Slurp(dir / "b" / relative)) << relative;
    ++files;
  }
  EXPECT_EQ(files, 3 * 3 + 7);  // rgb, depth, mask per frame; 6 lists and the marker
  fs::remove_all(dir);
}

TEST(SynthSequence, OptionsCheckRefusesBadValues) {
  SynthOptions o;
  EXPECT_NO_THROW(o.Check());
  o.frames = 0;
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.fps = 0;
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.camera = CameraPreset("freiburg1");  // distorted: we render pinhole images only
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.render.depth.min_range_m = 5;
  EXPECT_THROW(o.Check(), Error);
  try {
    ParsePreset("walking");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("walking_halfsphere"), std::string::npos) << "lists the known names";
  }
}

TEST(SynthSequence, ReplayKeepsTheFrameTimesInsideTheTrajectoryUpToFrames) {
  Trajectory gt;
  for (int k = 0; k <= 200; ++k) {
    gt.emplace_back(50.0 + k * 0.01, SE3d(SO3d::Exp(Eigen::Vector3d(0, 0.002 * k, 0)), Eigen::Vector3d(0.001 * k, 0, 0)));
  }
  SynthOptions o;
  o.preset = Preset::kWalkingRpy;
  o.frames = 40;
  ReplaySource replay{gt, {49.0, 49.5, 50.0, 50.5, 51.0, 51.5, 52.0, 52.5}};
  const SynthSequence s(o, replay);
  ASSERT_EQ(s.size(), 5);
  EXPECT_EQ(s.dropped_before(), 2);
  EXPECT_EQ(s.dropped_after(), 1);
  EXPECT_DOUBLE_EQ(s.camera_path()[0].timestamp, 50.0);
  EXPECT_EQ(s.frames_outside_free_space(), 0);
  EXPECT_DOUBLE_EQ(s.Render(2).scene_time, 1.0);
  replay.frame_times.clear();  // 30 Hz over the 2 s: 61 times, limited to 40 frames
  EXPECT_EQ(SynthSequence(o, replay).size(), 40);
  replay.frame_times = {10.0, 11.0};
  EXPECT_EQ(SynthSequence(o, replay).size(), 0) << "all outside: the caller reports it";
}

}  // namespace
}  // namespace dlslam::synth
