#include "dlslam/place/test_sequences.h"

#include <random>

#include "dlslam/data/camera.h"
#include "dlslam/features/orb_extractor.h"
#include "dlslam/io/image_io.h"
#include "dlslam/io/image_list.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/synth/renderer.h"
#include "dlslam/util/check.h"

namespace dlslam::place::testing {

std::vector<RevisitFrame> LoadRevisitFrames(const std::filesystem::path& dir, int stride,
                                            const Vocabulary& vocabulary) {
  const io::ImageList list = io::ReadImageList(dir / "rgb.txt");
  const Trajectory truth = io::ReadTumTrajectory(dir / "groundtruth.txt");
  DLSLAM_CHECK_EQ(list.images.size(), truth.size(), "one ground-truth pose per image expected in {}", dir.string());
  features::OrbExtractor extractor;
  std::vector<RevisitFrame> frames;
  for (std::size_t i = 0; i < list.images.size(); i += static_cast<std::size_t>(stride)) {
    const cv::Mat image = io::ReadColorImage({dir / list.images[i].path, list.images[i].list_file, list.images[i].line}, 0, 0);
    const auto descriptors = DescriptorsFromMat(extractor.Extract(image).descriptors);
    frames.push_back({static_cast<int>(i), truth[i].world_from_cam(), vocabulary.Transform(descriptors)});
  }
  return frames;
}

cv::Mat RenderColour(const synth::Scene& scene, const SE3d& world_from_cam, std::uint32_t noise_seed) {
  std::mt19937 rng(noise_seed);
  synth::CameraState state;
  state.world_from_cam = world_from_cam;
  return synth::RenderFrame(scene, CameraPreset("freiburg3"), state, synth::RenderOptions(), rng).colour;
}

}  // namespace dlslam::place::testing
