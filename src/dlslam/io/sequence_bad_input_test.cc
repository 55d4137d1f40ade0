// Every kind of bad sequence input gives an InputError that names the file
// (and the list line that referenced a bad image), never a crash or garbage.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <opencv2/imgcodecs.hpp>

#include "dlslam/io/sequence.h"
#include "dlslam/io/sequence_test_folder.h"
#include "dlslam/util/check.h"
#include "dlslam/util/crc32.h"

namespace dlslam::io {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::SequenceFolder;

std::string OpenError(const std::filesystem::path& dir, const RgbdSequenceOptions& options = {}) {
  try {
    RgbdSequence::Open(dir, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

std::string FrameError(const SequenceFolder& folder, std::size_t i) {
  const RgbdSequence seq = RgbdSequence::Open(folder.dir());
  const FrameLoadResult result = seq.TryLoadFrame(i);
  EXPECT_FALSE(result.ok());
  EXPECT_THROW(seq.LoadFrame(i), InputError);
  return result.error;
}

TEST(SequenceBadInput, MissingFolderOrLists) {
  SequenceFolder folder;
  EXPECT_THAT(OpenError(folder.dir() / "nope"), HasSubstr("sequence folder not found"));
  EXPECT_THAT(OpenError(folder.dir()), AllOf(HasSubstr("rgb.txt"), HasSubstr("file not found")));
  folder.WriteValidSequence(2);
  std::filesystem::remove(folder.dir() / "depth.txt");
  EXPECT_THAT(OpenError(folder.dir()), HasSubstr("depth.txt"));
}

TEST(SequenceBadInput, MalformedListLines) {
  SequenceFolder folder;
  folder.WriteValidSequence(3);
  folder.WriteText("rgb.txt", "# c\n1000.0 rgb/0.png\n1000.033333rgb/1.png\n");
  EXPECT_THAT(OpenError(folder.dir()),
              HasSubstr("rgb.txt:3: expected 'timestamp path', got 1 fields"));
  folder.WriteText("rgb.txt", "1000.0 rgb/0.png\nabc rgb/1.png\n");
  EXPECT_THAT(OpenError(folder.dir()),
              HasSubstr("rgb.txt:2: image timestamp 'abc' is not a finite number"));
  folder.WriteText("rgb.txt", "1000.0 rgb/0.png\n1000.1 rgb/1.png\n1000.05 rgb/2.png\n");
  EXPECT_THAT(OpenError(folder.dir()),
              HasSubstr("rgb.txt:3: image timestamp 1000.050000 is not larger"));
}

TEST(SequenceBadInput, NoAssociatedFrames) {
  SequenceFolder folder;
  folder.WriteValidSequence(2);
  folder.WriteText("depth.txt", "2000.0 depth/0.png\n");
  EXPECT_THAT(OpenError(folder.dir()), HasSubstr("no RGB image has a depth image within 0.02 s"));
}

TEST(SequenceBadInput, MissingImageInTheMiddleFailsOnlyThatFrame) {
  SequenceFolder folder;
  folder.WriteValidSequence(3);
  std::filesystem::remove(folder.dir() / "rgb/1.png");
  const RgbdSequence seq = RgbdSequence::Open(folder.dir());
  EXPECT_TRUE(seq.TryLoadFrame(0).ok());
  const FrameLoadResult lost = seq.TryLoadFrame(1);
  EXPECT_FALSE(lost.ok());
  EXPECT_THAT(lost.error, AllOf(HasSubstr("rgb.txt:4: colour image"), HasSubstr("rgb/1.png"),
                                HasSubstr("file not found")));
  EXPECT_TRUE(seq.TryLoadFrame(2).ok());
}

TEST(SequenceBadInput, MalformedMaskList) {
  SequenceFolder folder;
  folder.WriteValidSequence(2);
  folder.WriteText("mask.txt", "1000.0 mask/0.png\n1000.033333\n");
  EXPECT_THAT(OpenError(folder.dir()), HasSubstr("mask.txt:2: expected 'timestamp path', got 1 fields"));
  folder.WriteText("mask.txt", "1000.0 mask/0.png\n999.0 mask/1.png\n");
  EXPECT_THAT(OpenError(folder.dir()), HasSubstr("mask.txt:2: image timestamp 999.000000 is not larger"));
}

TEST(SequenceBadInput, BadMaskImagesFailTheirFrame) {
  SequenceFolder folder;
  folder.WriteValidSequence(4);
  folder.WriteMasks(4);
  std::filesystem::remove(folder.dir() / "mask/0.png");
  EXPECT_THAT(FrameError(folder, 0),
              AllOf(HasSubstr("mask.txt:3: mask image"), HasSubstr("mask/0.png"), HasSubstr("file not found")));
  cv::imwrite((folder.dir() / "mask/1.png").string(), cv::Mat(48, 64, CV_16UC1, cv::Scalar(300)));
  EXPECT_THAT(FrameError(folder, 1), AllOf(HasSubstr("mask.txt:4: mask image"), HasSubstr("16-bit image")));
  cv::imwrite((folder.dir() / "mask/2.png").string(), cv::Mat(48, 64, CV_8UC3, cv::Scalar(1, 2, 3)));
  EXPECT_THAT(FrameError(folder, 2), HasSubstr("3 channels, expected a single-channel"));
  cv::imwrite((folder.dir() / "mask/3.png").string(), cv::Mat(24, 32, CV_8UC1, cv::Scalar(0)));
  EXPECT_THAT(FrameError(folder, 3), HasSubstr("size 32x24 differs from the camera's 64x48"));
}

TEST(SequenceBadInput, EightBitDepth) {
  SequenceFolder folder;
  folder.WriteValidSequence(2);
  cv::imwrite((folder.dir() / "depth/1.png").string(), cv::Mat(48, 64, CV_8UC1, cv::Scalar(7)));
  EXPECT_THAT(FrameError(folder, 1), AllOf(HasSubstr("depth.txt:4: depth image"),
                                           HasSubstr("depth/1.png"), HasSubstr("8-bit")));
}

TEST(SequenceBadInput, WrongImageSize) {
  SequenceFolder folder;
  folder.WriteValidSequence(3);
  folder.WriteColor("rgb/1.png", {32, 48});
  folder.WriteDepth("depth/2.png", {64, 24}, 5000);
  EXPECT_THAT(
      FrameError(folder, 1),
      AllOf(HasSubstr("rgb/1.png"), HasSubstr("size 32x48 differs from the camera's 64x48")));
  EXPECT_THAT(FrameError(folder, 2), AllOf(HasSubstr("depth/2.png"), HasSubstr("size 64x24")));
}

TEST(SequenceBadInput, EmptyAndCorruptImageFiles) {
  SequenceFolder folder;
  folder.WriteValidSequence(3);
  folder.WriteText("depth/1.png", "");
  EXPECT_THAT(FrameError(folder, 1),
              AllOf(HasSubstr("depth/1.png"), HasSubstr("empty file (0 bytes)")));
  // A PNG signature followed by garbage.
  folder.WriteText("rgb/2.png", std::string("\x89PNG\r\n\x1a\n", 8) + "this is not image data");
  EXPECT_THAT(FrameError(folder, 2), AllOf(HasSubstr("rgb.txt:5"), HasSubstr("PNG")));
  // A real PNG cut in half.
  const auto path = folder.dir() / "depth/0.png";
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size / 2);
  EXPECT_THAT(FrameError(folder, 0), HasSubstr("depth/0.png"));
}

// Chunk checksums that add up over image data that does not inflate (a
// writer's bug, not a disk's): libpng grey-fills or fails without a reason;
// the frame fails, naming the file, its list line and the zlib stream.
TEST(SequenceBadInput, DepthPngWithValidChecksumsButBrokenImageDataFailsItsFrame) {
  SequenceFolder folder;
  folder.WriteValidSequence(3);
  cv::Mat depth(48, 64, CV_16UC1);  // WriteValidSequence's camera
  cv::randu(depth, 500, 5000);
  std::vector<uchar> png;
  ASSERT_TRUE(cv::imencode(".png", depth, png));
  // The first IDAT chunk: length (4), "IDAT", 2 bytes of zlib header, then
  // the first deflate block, whose type bits become the reserved type 3.
  std::size_t at = 8;
  while (at + 8 <= png.size() && std::string(reinterpret_cast<const char*>(&png[at + 4]), 4) != "IDAT") {
    at += 12 + (std::size_t{png[at]} << 24 | std::size_t{png[at + 1]} << 16 | std::size_t{png[at + 2]} << 8 |
                png[at + 3]);
  }
  ASSERT_LT(at + 11, png.size()) << "no IDAT chunk";
  const std::size_t length = std::size_t{png[at]} << 24 | std::size_t{png[at + 1]} << 16 |
                             std::size_t{png[at + 2]} << 8 | png[at + 3];
  png[at + 10] |= 0x06;
  const std::uint32_t crc =
      Crc32(std::vector<std::uint8_t>(png.begin() + static_cast<std::ptrdiff_t>(at + 4),
                                      png.begin() + static_cast<std::ptrdiff_t>(at + 8 + length)));
  for (int i = 0; i < 4; ++i) png[at + 8 + length + static_cast<std::size_t>(i)] = static_cast<uchar>(crc >> (24 - 8 * i));
  std::ofstream(folder.dir() / "depth/1.png", std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  EXPECT_TRUE(RgbdSequence::Open(folder.dir()).TryLoadFrame(0).ok());
  EXPECT_THAT(FrameError(folder, 1),
              AllOf(HasSubstr("depth/1.png"), HasSubstr("depth.txt:4"), HasSubstr("not a valid zlib stream")));
}

// OpenCV decodes a truncated JPEG into grey pixels with only a warning: the
// frame must fail instead of being tracked as if it were real.
TEST(SequenceBadInput, TruncatedOrCorruptJpegFailsItsFrame) {
  SequenceFolder folder;
  folder.WriteValidSequence(3);
  cv::Mat image(48, 64, CV_8UC3);  // WriteValidSequence's camera
  cv::randu(image, 0, 255);
  std::vector<uchar> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", image, jpeg));
  const auto write = [&](const std::string& name, std::size_t bytes) {
    std::ofstream(folder.dir() / name, std::ios::binary).write(reinterpret_cast<const char*>(jpeg.data()),
                                                                static_cast<std::streamsize>(bytes));
  };
  write("rgb/0.png", jpeg.size());  // a whole JPEG under a .png name: fine
  write("rgb/1.png", jpeg.size() * 9 / 10);
  EXPECT_TRUE(RgbdSequence::Open(folder.dir()).TryLoadFrame(0).ok());
  EXPECT_THAT(FrameError(folder, 1), AllOf(HasSubstr("rgb/1.png"), HasSubstr("truncated JPEG")));
}

// A list line naming a device or a FIFO fails that frame at once instead of
// reading without end (until std::bad_alloc ended the whole run).
TEST(SequenceBadInput, DevicesAndFifosAreNotImages) {
  SequenceFolder folder;
  folder.WriteValidSequence(3);
  std::filesystem::remove(folder.dir() / "depth/1.png");
  std::filesystem::create_symlink("/dev/zero", folder.dir() / "depth/1.png");
  EXPECT_THAT(FrameError(folder, 1), AllOf(HasSubstr("depth/1.png"), HasSubstr("not a regular file")));
  std::filesystem::remove(folder.dir() / "rgb/2.png");
  ASSERT_EQ(mkfifo((folder.dir() / "rgb/2.png").c_str(), 0600), 0);
  EXPECT_THAT(FrameError(folder, 2), AllOf(HasSubstr("rgb/2.png"), HasSubstr("not a regular file")));
  EXPECT_TRUE(RgbdSequence::Open(folder.dir()).TryLoadFrame(0).ok());
}

TEST(SequenceBadInput, ColourImageKinds) {
  SequenceFolder folder;
  folder.WriteValidSequence(2);
  // 8-bit grayscale becomes three equal channels (documented conversion).
  cv::imwrite((folder.dir() / "rgb/0.png").string(), cv::Mat(48, 64, CV_8UC1, cv::Scalar(90)));
  const RgbdFrame gray = RgbdSequence::Open(folder.dir()).LoadFrame(0);
  EXPECT_EQ(gray.color.type(), CV_8UC3);
  EXPECT_EQ(gray.color.at<cv::Vec3b>(3, 3), cv::Vec3b(90, 90, 90));
  // A depth image listed as colour.
  folder.WriteDepth("rgb/1.png", {64, 48}, 5000);
  EXPECT_THAT(FrameError(folder, 1), HasSubstr("16-bit image, expected 8-bit colour"));
}

TEST(SequenceBadInput, UnknownCamera) {
  SequenceFolder folder("recording_2024");
  folder.WriteValidSequence(2);
  std::filesystem::remove(folder.dir() / "camera.yaml");
  EXPECT_THAT(OpenError(folder.dir()),
              AllOf(HasSubstr("recording_2024"), HasSubstr("--camera"), HasSubstr("camera.yaml")));
  RgbdSequenceOptions options;
  options.camera_preset = "kinect7";
  EXPECT_THAT(OpenError(folder.dir(), options), HasSubstr("unknown camera preset 'kinect7'"));
  // A preset whose 640x480 does not match the 64x48 images fails per frame.
  options.camera_preset = "fr3";
  const RgbdSequence seq = RgbdSequence::Open(folder.dir(), options);
  EXPECT_THAT(seq.TryLoadFrame(0).error, HasSubstr("differs from the camera's 640x480"));
}

TEST(SequenceBadInput, MalformedSettings) {
  SequenceFolder folder;
  folder.WriteValidSequence(2);
  folder.WriteText("camera.yaml", "%YAML:1.0\nCamera.fx: [1,\n  Camera.fy: }\n");
  EXPECT_THAT(OpenError(folder.dir()), AllOf(HasSubstr("camera.yaml"), HasSubstr("malformed")));
  folder.WriteText("other.yaml",
                   "%YAML:1.0\nCamera.fx: 500.0\nCamera.fy: 500.0\nCamera.cx: 32.0\n");
  RgbdSequenceOptions options;
  options.settings_file = folder.dir() / "other.yaml";
  EXPECT_THAT(OpenError(folder.dir(), options),
              AllOf(HasSubstr("other.yaml"), HasSubstr("missing required key 'Camera.cy'")));
}

TEST(SequenceBadInput, MalformedGroundTruthAndAccelerometer) {
  SequenceFolder folder;
  folder.WriteValidSequence(2);
  folder.WriteText("groundtruth.txt", "1000.0 0 0 0 0 0 0 1\n1000.1 0 0 0 0 0\n");
  EXPECT_THAT(OpenError(folder.dir()), HasSubstr("groundtruth.txt:2"));
  std::filesystem::remove(folder.dir() / "groundtruth.txt");
  folder.WriteText("accelerometer.txt", "1000.0 0 9.8 x\n");
  EXPECT_THAT(OpenError(folder.dir()), HasSubstr("accelerometer.txt:1"));
}

TEST(SequenceBadInput, OptionsAreChecked) {
  RgbdSequenceOptions options;
  options.max_association_diff = -0.02;
  EXPECT_THROW(options.Check(), Error);
  options = {};
  options.depth_factor = -5000;
  EXPECT_THROW(options.Check(), Error);
  EXPECT_NO_THROW(RgbdSequenceOptions{}.Check());
}

}  // namespace
}  // namespace dlslam::io
