// `dlslam segment` run as a user runs it: masks written at the input size,
// sequences segmented frame by frame, bad input refused with the file named
// and a non-zero exit. Uses the tiny identity model (green = person) where the
// answer must be exact, and the shipped model once.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "tests/support/cli_run.h"
#include "tests/support/test_data.h"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using dlslam::testing::CliRun;
using dlslam::testing::Quoted;

// Runs the CLI through the shell with stderr folded into the output.
CliRun Cli(const std::string& args) {
  return dlslam::testing::RunShell(Quoted(DLSLAM_CLI_PATH) + " segment " + args + " 2>&1");
}

const cv::Rect kPerson(40, 30, 50, 60);

cv::Mat Frame(int shift) {
  cv::Mat frame(120, 160, CV_8UC3, cv::Scalar(128, 128, 128));
  frame(kPerson + cv::Point(shift, 0)).setTo(cv::Scalar(0, 255, 0));  // green: class 1 for the identity model
  return frame;
}

class SegmentCliTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = dlslam::testing::MakeTempDir("segment_cli"); }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string IdentityModel() {
    return "--model " + Quoted(dlslam::testing::FixturePath("semantic/identity_rgb.onnx"));
  }
  fs::path WriteFrame(const std::string& name, const cv::Mat& image) {
    cv::imwrite((dir_ / name).string(), image);
    return dir_ / name;
  }
  // A TUM-layout folder with `n` frames.
  fs::path MakeSequence(int n) {
    const fs::path seq = dir_ / "seq";
    fs::create_directories(seq / "rgb");
    std::ofstream list(seq / "rgb.txt");
    list << "# color images\n# timestamp filename\n";
    for (int i = 0; i < n; ++i) {
      const std::string name = "rgb/" + std::to_string(100 + i) + ".500000.png";
      cv::imwrite((seq / name).string(), Frame(4 * i));
      list << (100 + i) << ".500000 " << name << "\n";
    }
    return seq;
  }
  void ExpectError(const std::string& args, const std::string& words) {
    const CliRun run = Cli(args);
    EXPECT_EQ(run.exit_code, 1) << args << "\n" << run.output;
    EXPECT_THAT(run.output, HasSubstr("[error]")) << args;
    EXPECT_THAT(run.output, HasSubstr(words)) << args;
    EXPECT_THAT(run.output, ::testing::Not(HasSubstr("unexpected error"))) << args;
  }

  fs::path dir_;
};

TEST_F(SegmentCliTest, ImageMaskAndOverlay) {
  const fs::path image = WriteFrame("frame.png", Frame(0));
  const CliRun run = Cli("--image " + Quoted(image) + " --out " + Quoted(dir_ / "mask.png") + " --overlay " +
                         Quoted(dir_ / "overlay.png") + " --margin 0 " + IdentityModel());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const cv::Mat mask = cv::imread((dir_ / "mask.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(mask.type(), CV_8UC1);
  ASSERT_EQ(mask.size(), cv::Size(160, 120));
  EXPECT_EQ(cv::countNonZero(mask) + cv::countNonZero(mask == 0), 160 * 120);  // only 0 and 255
  const cv::Rect inner(kPerson.x + 3, kPerson.y + 3, kPerson.width - 6, kPerson.height - 6);
  EXPECT_EQ(cv::countNonZero(mask(inner)), inner.area());
  EXPECT_NEAR(cv::countNonZero(mask), kPerson.area(), 0.15 * kPerson.area());
  const cv::Mat overlay = cv::imread((dir_ / "overlay.png").string(), cv::IMREAD_COLOR);
  EXPECT_EQ(overlay.size(), cv::Size(160, 120));
  EXPECT_THAT(run.output, HasSubstr("dynamic"));
}

TEST_F(SegmentCliTest, ShippedModelByDefault) {
  const fs::path image = WriteFrame("wall.jpg", Frame(0));
  const CliRun run = Cli("--image " + Quoted(image) + " --out " + Quoted(dir_ / "m.png"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("dlslam_seg_mnv2_w05_209x273.onnx"));
  EXPECT_EQ(cv::imread((dir_ / "m.png").string(), cv::IMREAD_UNCHANGED).size(), cv::Size(160, 120));
}

TEST_F(SegmentCliTest, SequenceMasksNamedLikeTheFrames) {
  const fs::path seq = MakeSequence(5);
  const CliRun run =
      Cli("--sequence " + Quoted(seq) + " --out " + Quoted(dir_ / "masks") + " --margin 0 --every 2 " + IdentityModel());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("5 frames"));
  EXPECT_THAT(run.output, HasSubstr("3 segmented"));  // frames 0, 2, 4
  for (int i = 0; i < 5; ++i) {
    const fs::path mask_path = dir_ / "masks" / (std::to_string(100 + i) + ".500000.png");
    const cv::Mat mask = cv::imread(mask_path.string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(mask.size(), cv::Size(160, 120)) << mask_path;
    // Each frame's own square is inside its mask (propagated ones are grown).
    const cv::Rect inner = cv::Rect(kPerson.x + 4 * i + 3, kPerson.y + 3, kPerson.width - 6, kPerson.height - 6);
    EXPECT_EQ(cv::countNonZero(mask(inner)), inner.area()) << mask_path;
  }
  std::ifstream list(dir_ / "masks" / "mask.txt");
  std::string text((std::istreambuf_iterator<char>(list)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("100.500000 100.500000.png\n"));
  EXPECT_THAT(text, HasSubstr("104.500000 104.500000.png\n"));
}

TEST_F(SegmentCliTest, BadImages) {
  ExpectError("--image " + Quoted(dir_ / "none.png") + " " + IdentityModel(), "none.png': file not found");
  std::ofstream(dir_ / "garbage.png") << "not a png at all";
  ExpectError("--image " + Quoted(dir_ / "garbage.png") + " " + IdentityModel(), "garbage.png");
  const fs::path deep = WriteFrame("deep.png", cv::Mat(120, 160, CV_16UC1, cv::Scalar(1000)));
  ExpectError("--image " + Quoted(deep) + " " + IdentityModel(), "16-bit");
  const fs::path tiny = WriteFrame("tiny.png", cv::Mat(4, 4, CV_8UC3, cv::Scalar(0)));
  ExpectError("--image " + Quoted(tiny) + " " + IdentityModel(), "tiny.png: image of 4x4 px is smaller than 16 px");
}

TEST_F(SegmentCliTest, BadModels) {
  const fs::path image = WriteFrame("frame.png", Frame(0));
  ExpectError("--image " + Quoted(image) + " --model " + Quoted(dir_ / "missing.onnx"), "missing.onnx");
  std::ofstream(dir_ / "garbage.onnx") << "garbage garbage garbage";
  ExpectError("--image " + Quoted(image) + " --model " + Quoted(dir_ / "garbage.onnx"), "not a loadable ONNX");
  ExpectError("--image " + Quoted(image) + " --model " +
                  Quoted(dlslam::testing::FixturePath("semantic/two_classes.onnx")),
              "two_classes.onnx: ONNX model output is 1 x 2 x 209 x 273");
}

TEST_F(SegmentCliTest, BadSequences) {
  ExpectError("--sequence " + Quoted(dir_ / "nowhere") + " --out " + Quoted(dir_ / "m"), "sequence folder not found");
  fs::create_directories(dir_ / "empty");
  ExpectError("--sequence " + Quoted(dir_ / "empty") + " --out " + Quoted(dir_ / "m"), "rgb.txt");
  const fs::path seq = MakeSequence(2);
  ExpectError("--sequence " + Quoted(seq) + " " + IdentityModel(), "--out");
  ExpectError("--sequence " + Quoted(seq) + " --out " + Quoted(seq / "rgb") + " " + IdentityModel(),
              "folder of the colour frames");
  cv::imwrite((seq / "rgb" / "101.500000.png").string(), cv::Mat(8, 8, CV_8UC3, cv::Scalar(0)));
  ExpectError("--sequence " + Quoted(seq) + " --out " + Quoted(dir_ / "m") + " " + IdentityModel(),
              "rgb.txt:4: colour image '" + (seq / "rgb" / "101.500000.png").string() + "': image of 8x8 px");
  fs::remove(seq / "rgb" / "101.500000.png");
  ExpectError("--sequence " + Quoted(seq) + " --out " + Quoted(dir_ / "m") + " " + IdentityModel(),
              "rgb.txt:4: colour image");
}

TEST_F(SegmentCliTest, NeedsExactlyOneInput) {
  ExpectError("", "--image IMG or --sequence DIR");
  const CliRun both = Cli("--image a.png --sequence b");
  EXPECT_NE(both.exit_code, 0);
  EXPECT_THAT(both.output, HasSubstr("excludes"));
}

}  // namespace
