// The OpenCV-dnn backend on tiny fixture models (tests/fixtures/semantic,
// made by make_fixtures.py) whose answers are known exactly, and every bad
// model and bad frame we can think of.

#include "dlslam/semantic/onnx_segmenter.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgproc.hpp>
#include <random>

#include "dlslam/semantic/label_maps.h"
#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::semantic {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path Fixture(const std::string& name) { return dlslam::testing::FixturePath("semantic/" + name); }
fs::path ShippedModel() { return dlslam::testing::SourceDir() / "models" / kDefaultModelFile; }

SegmenterOptions IdentityOptions(int margin_px = 0) {
  SegmenterOptions options;
  options.model_path = Fixture("identity_rgb.onnx");
  options.dynamic_margin_px = margin_px;
  return options;
}

// A grey frame (all channels 0 after preprocessing: a tie, so background)
// with a green rectangle (class 1 = G after the BGR->RGB swap) and a blue one
// (class 2).
const cv::Rect kGreen(200, 100, 130, 160);
const cv::Rect kBlue(420, 300, 120, 100);
cv::Mat ColouredFrame() {
  cv::Mat frame(480, 640, CV_8UC3, cv::Scalar(128, 128, 128));
  frame(kGreen).setTo(cv::Scalar(0, 255, 0));
  frame(kBlue).setTo(cv::Scalar(255, 0, 0));
  return frame;
}

cv::Rect Grow(const cv::Rect& r, int px) { return {r.x - px, r.y - px, r.width + 2 * px, r.height + 2 * px}; }

// Pixels of `mask` inside `inner` all set, outside `outer` none.
void ExpectMaskBetween(const cv::Mat& mask, const cv::Rect& inner, const cv::Rect& outer, const char* what) {
  EXPECT_EQ(cv::countNonZero(mask(inner)), inner.area()) << what;
  cv::Mat outside = mask.clone();
  outside(outer & cv::Rect(0, 0, mask.cols, mask.rows)).setTo(0);
  EXPECT_EQ(cv::countNonZero(outside), 0) << what;
}

TEST(OnnxSegmenter, IdentityModelGivesTheColouredShapes) {
  OnnxSegmenter segmenter(IdentityOptions());
  const SegmentationResult r = segmenter.Segment(ColouredFrame());
  ASSERT_EQ(r.labels.size(), cv::Size(640, 480));
  ASSERT_EQ(r.labels.type(), CV_8UC1);
  ASSERT_EQ(r.dynamic_mask.type(), CV_8UC1);
  EXPECT_EQ(r.propagated_from, 0);
  EXPECT_GT(r.seconds, 0.0);
  // Resizing to 273 x 209 and back moves an edge by up to ~2 px.
  ExpectMaskBetween(r.dynamic_mask, Grow(kGreen, -3), Grow(kGreen, 3), "dynamic");
  ExpectMaskBetween(r.movable_mask, Grow(kBlue, -3), Grow(kBlue, 3), "movable");
  EXPECT_EQ(cv::countNonZero(r.labels == 1), cv::countNonZero(r.dynamic_mask));
  // Only 0 and 255 in masks.
  EXPECT_EQ(cv::countNonZero(r.dynamic_mask) + cv::countNonZero(r.dynamic_mask == 0), 640 * 480);
}

TEST(OnnxSegmenter, DynamicMaskGrowsByTheMargin) {
  OnnxSegmenter plain(IdentityOptions(0));
  OnnxSegmenter grown(IdentityOptions(8));
  const SegmentationResult a = plain.Segment(ColouredFrame());
  const SegmentationResult b = grown.Segment(ColouredFrame());
  ExpectMaskBetween(b.dynamic_mask, Grow(kGreen, 8 - 3), Grow(kGreen, 8 + 3), "dilated by 8");
  EXPECT_EQ(cv::countNonZero(b.dynamic_mask != DilateMask(a.dynamic_mask, 8)), 0);
  EXPECT_EQ(cv::countNonZero(a.labels != b.labels), 0);             // labels are not dilated
  EXPECT_EQ(cv::countNonZero(a.movable_mask != b.movable_mask), 0);  // nor movable objects
}

TEST(OnnxSegmenter, AnyFrameSizeComesBackAtItsOwnSize) {
  OnnxSegmenter segmenter(IdentityOptions());
  for (const cv::Size size : {cv::Size(16, 16), cv::Size(273, 209), cv::Size(1023, 77)}) {
    const SegmentationResult r = segmenter.Segment(cv::Mat(size, CV_8UC3, cv::Scalar(0, 255, 0)));
    EXPECT_EQ(r.labels.size(), size);
    EXPECT_EQ(cv::countNonZero(r.dynamic_mask), size.area());
  }
}

TEST(OnnxSegmenter, RefusesBadFrames) {
  OnnxSegmenter segmenter(IdentityOptions());
  const auto expect_error = [&](const cv::Mat& frame, const std::string& words) {
    try {
      segmenter.Segment(frame);
      ADD_FAILURE() << "no error for " << words;
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(words));
    }
  };
  expect_error(cv::Mat(), "empty image");
  expect_error(cv::Mat(48, 64, CV_8UC1, cv::Scalar(0)), "CV_8UC3), got 1 channel(s) of 8-bit");
  expect_error(cv::Mat(48, 64, CV_8UC4, cv::Scalar(0)), "got 4 channel(s)");
  expect_error(cv::Mat(48, 64, CV_16UC3, cv::Scalar(0)), "of 16-bit");
  expect_error(cv::Mat(48, 64, CV_32FC3, cv::Scalar(0)), "CV_8UC3");
  expect_error(cv::Mat(8, 64, CV_8UC3, cv::Scalar(0)), "smaller than 16 px");
}

class BadModelTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = dlslam::testing::MakeTempDir("bad_model"); }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path Write(const std::string& name, const std::string& bytes) {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return dir_ / name;
  }
  // The InputError of loading `model` (names the file), or a failure.
  static std::string LoadError(const fs::path& model, SegmenterOptions options = {}) {
    options.model_path = model;
    try {
      OnnxSegmenter segmenter(options);
      ADD_FAILURE() << "loaded " << model;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), model);
      EXPECT_THAT(e.what(), HasSubstr(model.string()));
      return e.what();
    }
    return {};
  }

  fs::path dir_;
};

TEST_F(BadModelTest, MissingOrEmptyFile) {
  EXPECT_THAT(LoadError(dir_ / "nothing.onnx"), HasSubstr("not found"));
  EXPECT_THAT(LoadError(Write("empty.onnx", "")), HasSubstr("empty"));
  EXPECT_THAT(LoadError(dir_), HasSubstr("a folder"));
}

TEST_F(BadModelTest, TruncatedOrGarbageFile) {
  std::ifstream in(ShippedModel(), std::ios::binary);
  const std::string model((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(model.size(), 100000u) << ShippedModel();
  EXPECT_THAT(LoadError(Write("half.onnx", model.substr(0, model.size() / 2))), HasSubstr("not a loadable ONNX"));
  EXPECT_THAT(LoadError(Write("tail_cut.onnx", model.substr(0, model.size() - 64))),
              HasSubstr("not a loadable ONNX"));
  std::string garbage(5000, '\0');
  std::mt19937 rng(3);
  for (char& c : garbage) c = static_cast<char>(rng() & 0xff);
  EXPECT_THAT(LoadError(Write("garbage.onnx", garbage)), HasSubstr("not a loadable ONNX"));
  EXPECT_THAT(LoadError(Write("text.onnx", "this is not a model\n")), HasSubstr("ONNX"));
}

TEST_F(BadModelTest, NoDeclaredSizeNeedsOneGiven) {
  EXPECT_THAT(LoadError(Fixture("any_size.onnx")), HasSubstr("declares no fixed 1 x 3 x H x W input"));
  SegmenterOptions sized;
  sized.model_path = Fixture("any_size.onnx");
  sized.input_width = 273;
  sized.input_height = 209;
  const OnnxSegmenter segmenter(sized);
  EXPECT_EQ(segmenter.options().input_width, 273);
}

TEST_F(BadModelTest, ASizeGivenMustBeTheModels) {
  SegmenterOptions other;
  other.input_width = 337;
  other.input_height = 257;
  EXPECT_THAT(LoadError(ShippedModel(), other), HasSubstr("1 x 3 x 257 x 337"));
}

TEST_F(BadModelTest, WrongOutputShape) {
  EXPECT_THAT(LoadError(Fixture("two_classes.onnx")), HasSubstr("output is 1 x 2 x 209 x 273"));
  EXPECT_THAT(LoadError(Fixture("half_size.onnx")), HasSubstr("output is 1 x 3 x 105 x 137"));
  EXPECT_THAT(LoadError(Fixture("vector_output.onnx")), HasSubstr("output is 1 x 3 ("));
  // A good model with options that do not fit it: another class count.
  SegmenterOptions voc;
  voc.num_classes = 21;
  voc.dynamic_classes = {15};
  voc.movable_classes = {9};
  EXPECT_THAT(LoadError(ShippedModel(), voc), HasSubstr("expected 1 x 21 x 209 x 273"));
}

TEST(OnnxSegmenterOptions, CheckNamesTheBadValue) {
  SegmenterOptions options = IdentityOptions();
  options.dynamic_classes = {3};
  EXPECT_THROW(OnnxSegmenter{options}, Error);
  options = IdentityOptions();
  options.movable_classes = {1};  // also dynamic
  EXPECT_THROW(OnnxSegmenter{options}, Error);
  options = IdentityOptions();
  options.input_width = 0;  // one side given, the other the model's: refused
  options.input_height = 209;
  EXPECT_THROW(OnnxSegmenter{options}, Error);
  options = IdentityOptions();
  options.input_width = -273;
  options.input_height = -209;
  EXPECT_THROW(OnnxSegmenter{options}, Error);
  options = IdentityOptions();
  options.backend = "tensorrt";
  EXPECT_THROW(MakeSegmenter(options), Error);
  options = IdentityOptions();
  options.dynamic_margin_px = -1;
  EXPECT_THROW(MakeSegmenter(options), Error);
}

TEST(OnnxSegmenter, RunsAtTheSizeTheModelDeclares) {
  const OnnxSegmenter shipped(SegmenterOptions{.model_path = ShippedModel()});
  EXPECT_EQ(shipped.options().input_width, 273);
  EXPECT_EQ(shipped.options().input_height, 209);
}

TEST(OnnxSegmenter, RunsATeacherAtItsOwnSizeWithoutSizeOptions) {
  DLSLAM_REQUIRE_SHARED_DATA(path, "models/deeplabv3-mnv2-voc/deeplabv3_mnv2_dm05_voc_257x337.onnx");
  SegmenterOptions voc{.model_path = path};
  voc.num_classes = 21;
  voc.dynamic_classes = {15};
  voc.movable_classes = {9};
  OnnxSegmenter teacher(voc);
  EXPECT_EQ(teacher.options().input_width, 337);
  EXPECT_EQ(teacher.options().input_height, 257);
  EXPECT_EQ(teacher.Segment(ColouredFrame()).labels.size(), cv::Size(640, 480));
}

TEST(MakeSegmenter, LoadsTheShippedModelByDefault) {
  const std::unique_ptr<Segmenter> segmenter = MakeSegmenter(SegmenterOptions{});
  EXPECT_EQ(segmenter->options().model_path.filename(), kDefaultModelFile);
  EXPECT_EQ(segmenter->options().num_classes, 3);
  const SegmentationResult r = segmenter->Segment(cv::Mat(120, 160, CV_8UC3, cv::Scalar(90, 120, 150)));
  EXPECT_EQ(r.labels.size(), cv::Size(160, 120));
  EXPECT_EQ(r.dynamic_mask.size(), cv::Size(160, 120));
}

}  // namespace
}  // namespace dlslam::semantic
