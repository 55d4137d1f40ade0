// Seeded mutation tests of every reader of user files (issue 16): each valid
// file is mutated many times (bytes flipped, cut, inserted, repeated; numbers
// replaced by extremes; lines dropped or doubled; deep nesting) and the reader
// must either refuse it with a dlslam::Error that names the file, or return
// something sane (finite, in range, usable downstream). Any other exception,
// a crash or a hang fails. Deterministic: case i of a reader uses seed i, and
// a failure prints the seed and the mutation to replay it.
//
// Size: kCases mutations per reader (DLSLAM_FUZZ_CASES overrides), a few
// seconds in all in Release; CI also runs it under ASan + UBSan.

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "dlslam/eval/ate.h"
#include "dlslam/eval/rpe.h"
#include "dlslam/io/camera_source.h"
#include "dlslam/io/image_io.h"
#include "dlslam/io/image_list.h"
#include "dlslam/io/sequence.h"
#include "dlslam/io/settings.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/map/map_file.h"
#include "dlslam/place/vocabulary_file.h"
#include "dlslam/place/vocabulary_training.h"
#include "dlslam/semantic/onnx_segmenter.h"
#include "dlslam/util/check.h"
#include "dlslam/util/crc32.h"
#include "tests/support/landmark_scene.h"
#include "tests/support/test_data.h"

namespace dlslam {
namespace {

namespace fs = std::filesystem;

int Cases(int default_cases) {
  const char* text = std::getenv("DLSLAM_FUZZ_CASES");
  return text ? std::max(1, std::atoi(text)) : default_cases;
}

// Values that broke readers before: overflow, 32-bit wrap, signs, non-finite,
// hex floats, empty and huge tokens.
const std::vector<std::string> kExtremes = {
    "1e308", "-1e308", "1e400", "nan", "inf", "-inf", "4294967936", "18446744073709551616", "-1", "0",
    "-0", "1e-300", "0x1p3", "+5", "1e", ".", "--1", std::string(5000, '9'), "", "1,5", "\t", "\"1.0\""};

// One mutation of `valid`, described in `what` for the failure message.
std::string Mutate(const std::string& valid, std::mt19937& rng, std::string& what, bool text) {
  std::string s = valid;
  const auto pick = [&](std::size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  const int kinds = text ? 9 : 5;
  const int kind = static_cast<int>(pick(static_cast<std::size_t>(kinds)));
  switch (kind) {
    case 0: {  // flip bytes
      const std::size_t n = 1 + pick(8);
      for (std::size_t i = 0; i < n && !s.empty(); ++i) s[pick(s.size())] ^= static_cast<char>(1 + pick(255));
      what = fmt::format("{} bytes flipped", n);
      break;
    }
    case 1: {  // truncate
      const std::size_t at = pick(s.size() + 1);
      s.resize(at);
      what = fmt::format("cut to {} bytes", at);
      break;
    }
    case 2: {  // insert random bytes
      const std::size_t at = pick(s.size() + 1), n = 1 + pick(32);
      std::string bytes;
      for (std::size_t i = 0; i < n; ++i) bytes += static_cast<char>(pick(256));
      s.insert(at, bytes);
      what = fmt::format("{} random bytes inserted at {}", n, at);
      break;
    }
    case 3: {  // repeat a slice
      const std::size_t at = pick(s.size()), n = 1 + pick(std::min<std::size_t>(s.size() - at, 4096));
      s.insert(at, s.substr(at, n));
      what = fmt::format("{} bytes at {} repeated", n, at);
      break;
    }
    case 4: {  // delete a slice
      const std::size_t at = pick(s.size()), n = 1 + pick(std::min<std::size_t>(s.size() - at, 256));
      s.erase(at, n);
      what = fmt::format("{} bytes at {} deleted", n, at);
      break;
    }
    case 5: case 6: {  // replace a number by an extreme
      std::vector<std::pair<std::size_t, std::size_t>> numbers;
      for (std::size_t i = 0; i < s.size();) {
        if (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '-' || s[i] == '.') {
          std::size_t j = i;
          while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '.' || s[j] == '-' || s[j] == '+')) ++j;
          numbers.emplace_back(i, j - i);
          i = j;
        } else {
          ++i;
        }
      }
      if (numbers.empty()) break;
      const auto [at, n] = numbers[pick(numbers.size())];
      const std::string& extreme = kExtremes[pick(kExtremes.size())];
      what = fmt::format("number '{}' at {} replaced by '{}'", s.substr(at, n), at, extreme.substr(0, 20));
      s.replace(at, n, extreme);
      break;
    }
    case 7: {  // drop or double a line
      std::vector<std::size_t> starts = {0};
      for (std::size_t i = 0; i + 1 < s.size(); ++i) if (s[i] == '\n') starts.push_back(i + 1);
      const std::size_t line = pick(starts.size());
      const std::size_t begin = starts[line];
      const std::size_t end = line + 1 < starts.size() ? starts[line + 1] : s.size();
      if (pick(2)) {
        s.erase(begin, end - begin);
        what = fmt::format("line {} dropped", line + 1);
      } else {
        s.insert(end, s.substr(begin, end - begin));
        what = fmt::format("line {} doubled", line + 1);
      }
      break;
    }
    default: {  // nesting or a very long line
      const std::size_t at = pick(s.size() + 1);
      const std::string piece = pick(2) ? std::string(20000, '[') : std::string(200000, 'a');
      s.insert(at, piece);
      what = fmt::format("{} x '{}' inserted at {}", piece.size(), piece[0], at);
      break;
    }
  }
  if (what.empty()) what = "unchanged";
  return s;
}

// Runs `read` on `cases` mutations of `valid` written to `path`. `read`
// returns "" when what it read is sane, else why not.
// A refusal must name `path` or, for a sequence folder, `named` (its folder).
// `reseal` (optional) repairs the format's checksums after each mutation, so
// that the parser behind the checksum is reached too.
using Reseal = std::function<void(std::string&)>;
void Fuzz(const fs::path& path, const std::string& valid, bool text, int cases,
          const std::function<std::string(const fs::path&)>& read, const std::string& named = "",
          const Reseal& reseal = {}) {
  int refused = 0, accepted = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int seed = 0; seed < cases; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    std::string what;
    std::string bytes = Mutate(valid, rng, what, text);
    if (reseal) reseal(bytes);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    const std::string replay = fmt::format("{} seed {}: {}", path.filename().string(), seed, what);
    if (std::getenv("DLSLAM_FUZZ_VERBOSE")) std::cerr << replay << std::endl;  // the last line before a crash
    try {
      const std::string problem = read(path);
      EXPECT_EQ(problem, "") << "accepted but not sane: " << replay;
      ++accepted;
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_TRUE(message.find(path.filename().string()) != std::string::npos ||
                  (!named.empty() && message.find(named) != std::string::npos))
          << "refusal does not name the file: " << message << " (" << replay << ")";
      EXPECT_EQ(message.find("internal check failed"), std::string::npos) << message << " (" << replay << ")";
      EXPECT_LT(message.size(), 1500u) << replay;
      ++refused;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a dlslam::Error: " << e.what() << " (" << replay << ")";
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << fmt::format("{}: {} cases, {} refused, {} accepted sane, {:.2f} s\n", path.filename().string(),
                           cases, refused, accepted, seconds);
}

// The .dlv CRC-32 over everything before its last 4 bytes, little-endian.
void ResealVocabulary(std::string& bytes) {
  if (bytes.size() < 4) return;
  const std::uint32_t crc = Crc32(std::string_view(bytes.data(), bytes.size() - 4));
  for (int i = 0; i < 4; ++i) bytes[bytes.size() - 4 + i] = static_cast<char>((crc >> (8 * i)) & 0xFF);
}

// Every PNG chunk's CRC (big-endian, over type and data) where the chunk fits.
void ResealPng(std::string& bytes) {
  const auto u8 = [&](std::size_t i) { return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])); };
  for (std::size_t pos = 8; pos + 12 <= bytes.size();) {
    const std::uint32_t length = u8(pos) << 24 | u8(pos + 1) << 16 | u8(pos + 2) << 8 | u8(pos + 3);
    if (length > bytes.size() - pos - 12) return;
    const std::uint32_t crc = Crc32(std::string_view(bytes.data() + pos + 4, length + 4));
    for (int i = 0; i < 4; ++i) bytes[pos + 8 + length + i] = static_cast<char>((crc >> (24 - 8 * i)) & 0xFF);
    pos += 12 + length;
  }
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string SaneTrajectory(const Trajectory& t) {
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!t[i].translation.allFinite() || !(t[i].translation.lpNorm<Eigen::Infinity>() <= kMaxCoordinate)) {
      return "translation out of range";
    }
    if (std::abs(t[i].rotation.norm() - 1.0) > 2e-3) return "rotation not unit";
    if (i > 0 && !(t[i].timestamp > t[i - 1].timestamp)) return "timestamps not increasing";
  }
  return "";
}

class InputFuzzTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::MakeTempDir("input_fuzz");
    spdlog::set_level(spdlog::level::err);  // thousands of warnings about repaired input
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(InputFuzzTest, Trajectories) {
  std::string valid = "# timestamp tx ty tz qx qy qz qw\n";
  Trajectory gt;
  for (int i = 0; i < 40; ++i) {
    const double t = 1305031102.0 + 0.033 * i;
    valid += fmt::format("{:.6f} {:.4f} {:.4f} {:.4f} 0.0 {:.5f} 0.0 {:.5f}\n", t, 0.01 * i, -0.02 * i, 1.0 + 0.005 * i,
                         std::sin(0.01 * i), std::cos(0.01 * i));
    StampedPose pose;
    pose.timestamp = t;
    pose.translation = Eigen::Vector3d(0.01 * i, -0.02 * i, 1.0);
    gt.push_back(pose);
  }
  Fuzz(dir_ / "traj.txt", valid, true, Cases(600), [&](const fs::path& path) -> std::string {
    const Trajectory est = io::ReadTumTrajectory(path);
    if (std::string problem = SaneTrajectory(est); !problem.empty()) return problem;
    // Downstream: ATE and RPE either refuse (too few matches) or give finite numbers.
    try {
      const eval::AteResult ate = eval::ComputeAte(gt, est);
      if (!std::isfinite(ate.error.rmse)) return "ATE not finite";
      const eval::RpeResult rpe = eval::ComputeRpe(gt, est);
      if (!std::isfinite(rpe.translation.rmse)) return "RPE not finite";
    } catch (const Error& e) {
      if (std::string(e.what()).find("internal check failed") != std::string::npos) return e.what();
    }
    return "";
  });
}

TEST_F(InputFuzzTest, ImageListsAndAssociations) {
  std::string list = "# color images\n# timestamp filename\n";
  std::string associations;
  for (int i = 0; i < 30; ++i) {
    list += fmt::format("{:.6f} rgb/{:.6f}.png\n", 100.0 + 0.033 * i, 100.0 + 0.033 * i);
    associations += fmt::format("{0:.6f} rgb/{0:.6f}.png {1:.6f} depth/{1:.6f}.png\n", 100.0 + 0.033 * i,
                                100.01 + 0.033 * i);
  }
  const auto sane = [](const auto& times) -> std::string {
    for (std::size_t i = 0; i < times.size(); ++i) {
      if (!std::isfinite(times[i])) return "timestamp not finite";
    }
    return "";
  };
  Fuzz(dir_ / "rgb.txt", list, true, Cases(500), [&](const fs::path& path) {
    std::vector<double> times;
    for (const io::ListedImage& image : io::ReadImageList(path).images) times.push_back(image.timestamp);
    return sane(times);
  });
  Fuzz(dir_ / "associations.txt", associations, true, Cases(500), [&](const fs::path& path) {
    std::vector<double> times;
    for (const io::AssociatedImages& pair : io::ReadAssociationFile(path)) {
      times.push_back(pair.rgb.timestamp);
      times.push_back(pair.depth.timestamp);
    }
    return sane(times);
  });
}

TEST_F(InputFuzzTest, SettingsAndIntrinsics) {
  const std::string settings = R"(%YAML:1.0
File.version: "1.0"
Camera.type: "PinHole"
Camera1.fx: 542.822841
Camera1.fy: 542.576870
Camera1.cx: 315.593520
Camera1.cy: 237.756098
Camera1.k1: 0.039903
Camera1.k2: -0.099343
Camera1.p1: -0.000730
Camera1.p2: -0.000144
Camera.width: 640
Camera.height: 480
Camera.fps: 30
Stereo.b: 0.0745
Stereo.ThDepth: 40.0
RGBD.DepthMapFactor: 5000.0
Stereo.T_c1_c2: !!opencv-matrix
  rows: 4
  cols: 4
  dt: f
  data: [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0, 0, 0, 1.0]
ORBextractor.nFeatures: 1000
Viewer.KeyFrameSize: 0.05
)";
  Fuzz(dir_ / "camera.yaml", settings, true, Cases(800), [](const fs::path& path) -> std::string {
    const io::CameraSettings read = io::ReadSettingsFile(path);
    CameraIntrinsics camera = read.camera;
    if (!read.has_image_size) camera.width = 640, camera.height = 480;
    try {
      camera.Check();
    } catch (const Error& e) {
      // Without a size in the file the caller checks later (with the image size).
      if (read.has_image_size) return std::string("accepted a camera that fails Check(): ") + e.what();
    }
    if (!(read.fps > 0 && read.fps <= 1000 && std::isfinite(read.th_depth))) return "fps or ThDepth out of range";
    return "";
  });
  Fuzz(dir_ / "camera-intrinsics.txt", "585.0 0.0 320.0\n0.0 585.0 240.0\n0.0 0.0 1.0\n", true, Cases(300),
       [](const fs::path& path) -> std::string {
         const CameraIntrinsics c = io::ReadIntrinsicsMatrix(path);
         return std::isfinite(c.fx) && c.fx > 0 && std::isfinite(c.cx) ? "" : "non-finite intrinsics";
       });
}

TEST_F(InputFuzzTest, Images) {
  cv::Mat colour(48, 64, CV_8UC3), depth(48, 64, CV_16UC1), mask(48, 64, CV_8UC1, cv::Scalar(0));
  cv::randu(colour, 0, 255);
  cv::randu(depth, 500, 20000);
  mask(cv::Rect(10, 10, 20, 20)).setTo(1);
  std::vector<uchar> png, jpeg, depth_png, mask_png;
  cv::imencode(".png", colour, png);
  cv::imencode(".jpg", colour, jpeg);
  cv::imencode(".png", depth, depth_png);
  cv::imencode(".png", mask, mask_png);
  const auto bytes = [](const std::vector<uchar>& v) { return std::string(v.begin(), v.end()); };
  const auto colour_reader = [](const fs::path& path) -> std::string {
    const cv::Mat image = io::ReadColorImage({path, {}, 0}, 64, 48);
    return image.type() == CV_8UC3 && image.cols == 64 && image.rows == 48 ? "" : "wrong type or size";
  };
  Fuzz(dir_ / "colour.png", bytes(png), false, Cases(300), colour_reader);
  Fuzz(dir_ / "resealed.png", bytes(png), false, Cases(300), colour_reader, "", ResealPng);
  Fuzz(dir_ / "colour.jpg", bytes(jpeg), false, Cases(300), colour_reader);
  Fuzz(dir_ / "depth.png", bytes(depth_png), false, Cases(300), [](const fs::path& path) -> std::string {
    const cv::Mat image = io::ReadDepthImage({path, {}, 0}, 5000.0, 64, 48);
    if (image.type() != CV_32FC1 || image.size() != cv::Size(64, 48)) return "wrong type or size";
    return cv::checkRange(image, true, nullptr, 0.0, 14.0) ? "" : "depth out of range";
  });
  Fuzz(dir_ / "mask.png", bytes(mask_png), false, Cases(300), [](const fs::path& path) -> std::string {
    const cv::Mat image = io::ReadMaskImage({path, {}, 0}, 64, 48);
    return image.type() == CV_8UC1 && image.size() == cv::Size(64, 48) ? "" : "wrong type or size";
  });
}

TEST_F(InputFuzzTest, Vocabularies) {
  place::TrainingDescriptors training;
  std::mt19937 rng(3);
  for (int image = 0; image < 4; ++image) {
    std::vector<Descriptor> descriptors(200);
    for (Descriptor& d : descriptors) {
      for (auto& word : d) word = rng();
    }
    training.AddImage(descriptors);
  }
  place::VocabularyOptions options;
  options.branching = 4;
  options.levels = 3;
  options.threads = 1;
  const std::string valid = place::SerializeVocabulary(place::TrainVocabulary(training, options));
  const auto probe = training.image(0);
  const auto read = [&](const fs::path& path) -> std::string {
    const place::Vocabulary vocabulary = place::ParseVocabulary(ReadText(path), path);
    // Usable: every descriptor lands on a word of the tree.
    place::BowVector bow;
    place::FeatureVector features;
    vocabulary.Transform(probe, 1, bow, features);
    for (const auto& [word, weight] : bow) {
      if (word >= vocabulary.word_count() || !std::isfinite(weight)) return "word or weight out of range";
    }
    return "";
  };
  Fuzz(dir_ / "vocab.dlv", valid, false, Cases(300), read);
  Fuzz(dir_ / "resealed.dlv", valid, false, Cases(500), read, "", ResealVocabulary);
}

// A map of three keyframes of a landmark room, each keypoint with depth a
// point, seen again by the next keyframe where it sees the same landmark.
std::string SmallMapFile() {
  const auto scene = testing::LandmarkScene::Room(1500, 5);
  Map map;
  std::vector<std::vector<int>> landmark_of(3);
  std::vector<KeyFrameId> ids;
  std::map<int, MapPointId> point_of_landmark;
  for (int k = 0; k < 3; ++k) {
    const SE3d pose(SO3d(), Eigen::Vector3d(0.05 * k, 0.0, 0.0));
    const auto frame = scene.MakeFrame(pose, k / 30.0, 7 + k, 0.5, 8, &landmark_of[k]);
    ids.push_back(map.AddKeyFrame(frame, pose));
    for (std::size_t i = 0; i < frame->size(); ++i) {
      const int landmark = landmark_of[k][i];
      if (const auto it = point_of_landmark.find(landmark); it != point_of_landmark.end()) {
        map.AddObservation(it->second, ids.back(), static_cast<int>(i));
      } else if (const auto p = frame->Unproject(i)) {
        point_of_landmark[landmark] = map.AddMapPoint(pose.Inverse() * *p, ids.back(), static_cast<int>(i));
      }
    }
    map.UpdateConnections(ids.back());
  }
  map.AddLoopEdge(ids.front(), ids.back());
  return SerializeMap(map.Export(), {scene.camera, scene.pyramid});
}

TEST_F(InputFuzzTest, MapFiles) {
  const std::string valid = SmallMapFile();
  const auto read = [](const fs::path& path) -> std::string {
    Map map;
    ParseMap(ReadText(path), path, &map);
    // Usable: every keyframe resolves, its local map can be searched.
    for (const KeyFramePose& k : map.KeyFramePoses()) {
      if (!k.cam_from_world.translation().allFinite()) return "non-finite pose";
      const auto keyframe = map.GetKeyFrame(k.id);
      if (!keyframe) return "a listed keyframe is missing";
      for (const MapPointView& p : map.GetLocalMap(keyframe->points).points) {
        if (!p.position.allFinite()) return "non-finite point";
      }
    }
    return "";
  };
  Fuzz(dir_ / "room.dlmap", valid, false, Cases(300), read);
  Fuzz(dir_ / "resealed.dlmap", valid, false, Cases(500), read, "", ResealVocabulary);  // the same CRC layout
}

TEST_F(InputFuzzTest, SegmentationModels) {
  const fs::path fixture = testing::FixturePath("semantic/identity_rgb.onnx");
  semantic::SegmenterOptions options;
  options.dynamic_margin_px = 0;
  const cv::Mat frame(48, 64, CV_8UC3, cv::Scalar(20, 200, 20));
  Fuzz(dir_ / "model.onnx", ReadText(fixture), false, Cases(300), [&](const fs::path& path) -> std::string {
    options.model_path = path;
    semantic::OnnxSegmenter segmenter(options);
    const cv::Mat labels = segmenter.Segment(frame).labels;
    return labels.size() == frame.size() && labels.type() == CV_8UC1 ? "" : "wrong label image";
  });
}

TEST_F(InputFuzzTest, SequenceFolders) {
  // A 4-frame TUM folder; rgb.txt, depth.txt and camera.yaml mutated in turn,
  // then opened and every frame read.
  const fs::path seq = dir_ / "seq";
  fs::create_directories(seq / "rgb");
  fs::create_directories(seq / "depth");
  std::string rgb = "# color images\n", depth = "# depth maps, depth factor 5000\n";
  for (int i = 0; i < 4; ++i) {
    const double t = 10.0 + 0.033 * i;
    cv::imwrite((seq / fmt::format("rgb/{:.6f}.png", t)).string(), cv::Mat(48, 64, CV_8UC3, cv::Scalar(i, 50, 90)));
    cv::imwrite((seq / fmt::format("depth/{:.6f}.png", t)).string(), cv::Mat(48, 64, CV_16UC1, cv::Scalar(6000)));
    rgb += fmt::format("{0:.6f} rgb/{0:.6f}.png\n", t);
    depth += fmt::format("{0:.6f} depth/{0:.6f}.png\n", t);
  }
  const std::string settings =
      "%YAML:1.0\nCamera.fx: 60.0\nCamera.fy: 60.0\nCamera.cx: 32.0\nCamera.cy: 24.0\nCamera.k1: 0.0\n"
      "Camera.k2: 0.0\nCamera.p1: 0.0\nCamera.p2: 0.0\nCamera.width: 64\nCamera.height: 48\nDepthMapFactor: 5000.0\n";
  std::ofstream(seq / "rgb.txt") << rgb;
  std::ofstream(seq / "depth.txt") << depth;
  std::ofstream(seq / "camera.yaml") << settings;
  const auto open_and_read = [&](const fs::path&) -> std::string {
    const io::RgbdSequence sequence = io::RgbdSequence::Open(seq);
    for (std::size_t i = 0; i < sequence.size(); ++i) {
      const io::RgbdFrame frame = sequence.LoadFrame(i);
      if (frame.depth.type() != CV_32FC1 || frame.color.size() != frame.depth.size()) return "frame mismatched";
      if (!cv::checkRange(frame.depth, true, nullptr, 0.0, 1e4)) return "depth out of range";
    }
    return "";
  };
  for (const auto& [name, valid] : {std::pair{"rgb.txt", rgb}, {"depth.txt", depth}, {"camera.yaml", settings}}) {
    Fuzz(seq / name, valid, true, Cases(150), open_and_read, seq.string());
    std::ofstream(seq / name, std::ios::trunc) << valid;
  }
}

}  // namespace
}  // namespace dlslam
