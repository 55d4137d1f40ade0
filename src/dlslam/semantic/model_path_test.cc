#include "dlslam/semantic/model_path.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::semantic {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class ModelPathTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = dlslam::testing::MakeTempDir("model_path");
    for (const char* sub : {"env", "installed", "source"}) fs::create_directories(dir_ / sub);
    search_ = {dir_ / "env", dir_ / "installed", dir_ / "source"};
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path Touch(const fs::path& path) {
    std::ofstream(path) << "x";
    return path;
  }

  fs::path dir_;
  ModelSearch search_;
};

TEST_F(ModelPathTest, ExplicitPathWinsAndMustExist) {
  const fs::path file = Touch(dir_ / "mine.onnx");
  Touch(dir_ / "env" / "m.onnx");
  EXPECT_EQ(ResolveModelPath(file, "m.onnx", search_), file);
  try {
    ResolveModelPath(dir_ / "missing.onnx", "m.onnx", search_);
    FAIL() << "no error for a missing explicit model";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), dir_ / "missing.onnx");
    EXPECT_THAT(e.what(), HasSubstr("not found"));
  }
  EXPECT_THROW(ResolveModelPath(dir_ / "env", "m.onnx", search_), InputError);  // a directory
}

TEST_F(ModelPathTest, FirstExistingPlaceInOrder) {
  Touch(dir_ / "source" / "m.onnx");
  EXPECT_EQ(ResolveModelPath("", "m.onnx", search_), dir_ / "source" / "m.onnx");
  Touch(dir_ / "installed" / "m.onnx");
  EXPECT_EQ(ResolveModelPath("", "m.onnx", search_), dir_ / "installed" / "m.onnx");
  Touch(dir_ / "env" / "m.onnx");
  EXPECT_EQ(ResolveModelPath("", "m.onnx", search_), dir_ / "env" / "m.onnx");
  search_.env_dir.clear();  // unset variable: skipped
  EXPECT_EQ(ResolveModelPath("", "m.onnx", search_), dir_ / "installed" / "m.onnx");
}

TEST_F(ModelPathTest, NotFoundListsEveryPlaceTried) {
  search_.env_dir.clear();
  try {
    ResolveModelPath("", "m.onnx", search_);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_THAT(what, HasSubstr("DLSLAM_MODEL_DIR (not set)"));
    EXPECT_THAT(what, HasSubstr((dir_ / "installed" / "m.onnx").string()));
    EXPECT_THAT(what, HasSubstr((dir_ / "source" / "m.onnx").string()));
    EXPECT_THAT(what, HasSubstr("--model"));
    EXPECT_EQ(what.find('\n'), std::string::npos);  // one line for the CLI
  }
}

TEST(DefaultModelSearch, FindsTheShippedModelInTheSourceTree) {
  // The build bakes in <source>/models, so a build tree runs without setup.
  const ModelSearch search = DefaultModelSearch();
  EXPECT_EQ(search.installed_dir.filename(), "models");
  EXPECT_TRUE(fs::is_regular_file(search.source_models_dir / "dlslam_seg_mnv2_w05_257x337.onnx"))
      << search.source_models_dir;
}

}  // namespace
}  // namespace dlslam::semantic
