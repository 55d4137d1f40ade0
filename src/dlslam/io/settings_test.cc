#include "dlslam/io/settings.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::io {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

constexpr const char* kOldLayout = R"(%YAML:1.0
# an RGB-D camera
Camera.fx: 517.306408
Camera.fy: 516.469215
Camera.cx: 318.643040
Camera.cy: 255.313989

Camera.k1: 0.262383
Camera.k2: -0.953104
Camera.p1: -0.005358
Camera.p2: 0.002628
Camera.k3: 1.163314

Camera.width: 640
Camera.height: 480
Camera.fps: 30.0
Camera.bf: 40.0
Camera.RGB: 1
ThDepth: 40.0
DepthMapFactor: 5000.0
)";

class SettingsTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::MakeTempDir("settings"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  // kOldLayout with the line starting with `key` replaced (or removed).
  std::filesystem::path WriteOldLayoutWith(const std::string& key, const std::string& line) {
    std::istringstream in(kOldLayout);
    std::string text, out;
    while (std::getline(in, text)) {
      if (text.rfind(key + ":", 0) == 0) {
        if (!line.empty()) out += line + "\n";
      } else {
        out += text + "\n";
      }
    }
    return Write("edited.yaml", out);
  }
  static std::string ErrorOf(const std::filesystem::path& path) {
    try {
      ReadSettingsFile(path);
    } catch (const InputError& e) {
      return e.what();
    }
    return "<no error>";
  }
  std::filesystem::path dir_;
};

TEST_F(SettingsTest, ReadsOldLayout) {
  const CameraSettings s = ReadSettingsFile(Write("cam.yaml", kOldLayout));
  EXPECT_EQ(s.camera.name, "settings:cam.yaml");
  EXPECT_DOUBLE_EQ(s.camera.fx, 517.306408);
  EXPECT_DOUBLE_EQ(s.camera.cy, 255.313989);
  EXPECT_DOUBLE_EQ(s.camera.k2, -0.953104);
  EXPECT_DOUBLE_EQ(s.camera.k3, 1.163314);
  EXPECT_EQ(s.camera.width, 640);
  EXPECT_EQ(s.camera.height, 480);
  EXPECT_TRUE(s.has_image_size);
  EXPECT_TRUE(s.has_depth_factor);
  EXPECT_DOUBLE_EQ(s.camera.depth_factor, 5000.0);
  EXPECT_DOUBLE_EQ(s.camera.bf, 40.0);
  EXPECT_DOUBLE_EQ(s.fps, 30.0);
}

TEST_F(SettingsTest, ReadsVersion1Layout) {
  const auto path = Write("v1.yaml", R"(%YAML:1.0
File.version: "1.0"
Camera.type: "PinHole"
Camera1.fx: 535.4
Camera1.fy: 539.2
Camera1.cx: 320.1
Camera1.cy: 247.6
Camera1.k1: 0.0
Camera1.k2: 0.0
Camera1.p1: 0.0
Camera1.p2: 0.0
Camera.width: 640
Camera.height: 480
Camera.fps: 30
Camera.RGB: 1
Stereo.ThDepth: 40.0
Stereo.b: 0.07732
RGBD.DepthMapFactor: 1000.0
)");
  const CameraSettings s = ReadSettingsFile(path);
  EXPECT_DOUBLE_EQ(s.camera.fx, 535.4);
  EXPECT_DOUBLE_EQ(s.camera.cy, 247.6);
  EXPECT_FALSE(s.camera.HasDistortion());
  EXPECT_DOUBLE_EQ(s.camera.bf, 0.07732 * 535.4);
  EXPECT_DOUBLE_EQ(s.camera.depth_factor, 1000.0);
  EXPECT_EQ(s.camera.width, 640);
}

TEST_F(SettingsTest, SizeAndDepthFactorAreOptional) {
  auto path = WriteOldLayoutWith("Camera.width", "");
  EXPECT_THAT(ErrorOf(path), HasSubstr("missing required key 'Camera.width'"));
  std::string text = kOldLayout;
  for (const char* key :
       {"Camera.width: 640\n", "Camera.height: 480\n", "DepthMapFactor: 5000.0\n"}) {
    text.erase(text.find(key), std::string(key).size());
  }
  const CameraSettings s = ReadSettingsFile(Write("orbslam2.yaml", text));
  EXPECT_FALSE(s.has_image_size);
  EXPECT_EQ(s.camera.width, 0);
  EXPECT_FALSE(s.has_depth_factor);
}

TEST_F(SettingsTest, WriteThenReadIsLosslessAndOrbSlamReadable) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  CameraIntrinsics c = CameraPreset("freiburg1");
  c.name = "random";
  c.fx = 500 + 100 * std::abs(u(rng));
  c.cx = 320 + 10 * u(rng);
  c.k1 = 1e-5 * u(rng);
  c.p2 = 0.0;
  c.depth_factor = 1000.0;
  c.bf = 38.123456789;
  const auto path = dir_ / "written.yaml";
  WriteCameraSettings(path, c, 30.0);
  const CameraSettings s = ReadSettingsFile(path);
  EXPECT_EQ(s.camera.fx, c.fx);
  EXPECT_EQ(s.camera.cx, c.cx);
  EXPECT_EQ(s.camera.k1, c.k1);
  EXPECT_EQ(s.camera.k3, c.k3);
  EXPECT_EQ(s.camera.bf, c.bf);
  EXPECT_EQ(s.camera.depth_factor, 1000.0);
  EXPECT_EQ(s.camera.width, 640);
  EXPECT_DOUBLE_EQ(s.fps, 30.0);
  std::ifstream in(path);
  std::string first_line;
  std::getline(in, first_line);
  EXPECT_EQ(first_line, "%YAML:1.0");
  std::stringstream all;
  all << in.rdbuf();
  // ORB-SLAM3 reads these with FileNode::isReal(): "0" would be an integer.
  EXPECT_THAT(all.str(), HasSubstr("Camera.p2: 0.0\n"));
  EXPECT_THAT(all.str(), HasSubstr("DepthMapFactor: 1000.0\n"));
}

TEST_F(SettingsTest, WriterRejectsAnInvalidCamera) {
  CameraIntrinsics c;
  c.fx = -1;
  EXPECT_THROW(WriteCameraSettings(dir_ / "x.yaml", c, 30.0), Error);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.yaml"));
}

TEST_F(SettingsTest, MissingKeyNamesFileAndKey) {
  const std::string error = ErrorOf(WriteOldLayoutWith("Camera.fy", ""));
  EXPECT_THAT(error, HasSubstr("edited.yaml"));
  EXPECT_THAT(error, HasSubstr("missing required key 'Camera.fy'"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.k1", "")), HasSubstr("'Camera.k1'"));
}

TEST_F(SettingsTest, NonNumericValueNamesKeyAndLine) {
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.fx", "Camera.fx: abc")),
              HasSubstr("edited.yaml:3: key 'Camera.fx': expected a number, got text 'abc'"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.cx", "Camera.cx: [1, 2]")),
              HasSubstr("key 'Camera.cx': expected a number, got a list"));
}

TEST_F(SettingsTest, ImplausibleValuesAreRejected) {
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.fx", "Camera.fx: -517.3")),
              HasSubstr("'Camera.fx': -517.3 outside [1, 1000000] px"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("DepthMapFactor", "DepthMapFactor: 0.0")),
              HasSubstr("'DepthMapFactor': 0 outside [0.01, 100000] raw units per metre"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.width", "Camera.width: 64.5")),
              HasSubstr("is not an image size"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.cx", "Camera.cx: 700.0")),
              HasSubstr("inconsistent camera"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.RGB", "Camera.type: \"KannalaBrandt8\"")),
              HasSubstr("only PinHole"));
}

TEST_F(SettingsTest, MalformedFilesAreInputErrors) {
  EXPECT_THAT(ErrorOf(dir_ / "none.yaml"), HasSubstr("none.yaml: file not found"));
  EXPECT_THAT(ErrorOf(Write("empty.yaml", "")), HasSubstr("empty settings file"));
  const std::string broken =
      ErrorOf(Write("broken.yaml", "%YAML:1.0\nCamera.fx: [535.4\nCamera.fy: {\n"));
  // The list opened on line 2 is still open when line 3 starts a new key.
  EXPECT_THAT(broken, HasSubstr("broken.yaml:3:"));
  EXPECT_THAT(broken, HasSubstr("malformed YAML"));
  const std::string text = ErrorOf(Write("text.yaml", "just some text\nnot yaml: [\n"));
  EXPECT_THAT(text, HasSubstr("text.yaml"));
}

TEST_F(SettingsTest, DeepNestingIsRefusedWithoutOverflowingTheStack) {
  // OpenCV's parser recursed once per '[' and crashed with SIGSEGV.
  for (const std::string& open : {std::string("["), std::string("{a: "), std::string("- ")}) {
    std::string deep = "%YAML:1.0\nCamera.fx: ";
    for (int i = 0; i < 100000; ++i) deep += open;
    EXPECT_THAT(ErrorOf(Write("deep.yaml", deep)), HasSubstr("deep.yaml")) << open;
  }
}

TEST_F(SettingsTest, NumbersAreReadWholeWithoutWrapAround) {
  // 4294967936 = 2^32 + 640 read as 640 through a 32-bit int.
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.width", "Camera.width: 4294967936")),
              HasSubstr("edited.yaml:14: key 'Camera.width': 4294967936 is not an image size"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.fx", "Camera.fx: 4294967831")),
              HasSubstr("key 'Camera.fx': 4294967831 outside [1, 1000000] px"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.fx", "Camera.fx: 517.3abc")),
              HasSubstr("expected a number, got text '517.3abc'"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.fx", "Camera.fx: .inf")), HasSubstr("expected a number"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.fx", "Camera.fx: 1e400")), HasSubstr("expected a number"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("DepthMapFactor", "DepthMapFactor: 1e-300")),
              HasSubstr("key 'DepthMapFactor': 1e-300 outside [0.01, 100000]"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("DepthMapFactor", "DepthMapFactor: 1e300")),
              HasSubstr("key 'DepthMapFactor': 1e+300 outside"));
  EXPECT_THAT(ErrorOf(WriteOldLayoutWith("Camera.k1", "Camera.k1: 1e10")),
              AllOf(HasSubstr("inconsistent camera"), HasSubstr("radial distortion")));
  EXPECT_EQ(ReadSettingsFile(WriteOldLayoutWith("Camera.fx", "Camera.fx: +517")).camera.fx, 517.0);
}

TEST_F(SettingsTest, AKeyGivenTwiceOrAListAtTheTopIsRefused) {
  EXPECT_THAT(ErrorOf(Write("twice.yaml", std::string(kOldLayout) + "Camera.fx: 600.0\n")),
              HasSubstr("twice.yaml:21: key 'Camera.fx' given twice (first on line 3)"));
  EXPECT_THAT(ErrorOf(Write("list.yaml", "%YAML:1.0\n- 1\n- 2\n")),
              HasSubstr("list.yaml:2: the top level must be 'key: value' lines, got a list"));
  EXPECT_THAT(ErrorOf(Write("comments.yaml", "%YAML:1.0\n# nothing\n")), HasSubstr("no settings"));
}

TEST_F(SettingsTest, SpecialFilesAndLongTokensAreRefusedBriefly) {
  EXPECT_THAT(ErrorOf("/dev/null"), HasSubstr("/dev/null: not a regular file"));
  EXPECT_THAT(ErrorOf(Write("huge.yaml", std::string(2 << 20, '#'))), HasSubstr("more than the 1 MB"));
  const std::string error =
      ErrorOf(WriteOldLayoutWith("Camera.fx", "Camera.fx: " + std::string(100000, 'x')));
  EXPECT_THAT(error, HasSubstr("(100000 characters)"));
  EXPECT_LT(error.size(), 300u);
}

}  // namespace
}  // namespace dlslam::io
