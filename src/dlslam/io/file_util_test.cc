#include "dlslam/io/file_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "dlslam/io/model_file.h"
#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::io {
namespace {

using ::testing::HasSubstr;

void WriteBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ReadFileBytes, ReturnsBinaryContentUnchanged) {
  const auto dir = dlslam::testing::MakeTempDir("read_bytes");
  const std::string bytes("a\0b\r\n\xff\0", 7);
  WriteBytes(dir / "x.bin", bytes);
  EXPECT_EQ(ReadFileBytes(dir / "x.bin"), bytes);
  WriteBytes(dir / "empty.bin", "");
  EXPECT_EQ(ReadFileBytes(dir / "empty.bin"), "");
  std::filesystem::remove_all(dir);
}

TEST(ReadFileBytes, MissingFileOrFolderIsAnInputErrorNamingThePath) {
  const auto dir = dlslam::testing::MakeTempDir("read_bytes_bad");
  EXPECT_THAT(ErrorOf([&] { ReadFileBytes(dir / "nope.bin"); }),
              ::testing::AllOf(HasSubstr("nope.bin"), HasSubstr("not found")));
  EXPECT_THAT(ErrorOf([&] { ReadFileBytes(dir); }), HasSubstr("a folder"));
  EXPECT_THAT(ErrorOf([&] { ReadFileBytes("/dev/zero"); }), HasSubstr("not a regular file"));
  std::filesystem::create_symlink(dir / "loop_a", dir / "loop_b");
  std::filesystem::create_symlink(dir / "loop_b", dir / "loop_a");
  EXPECT_THAT(ErrorOf([&] { ReadFileBytes(dir / "loop_a"); }),
              ::testing::AllOf(HasSubstr("loop_a"), HasSubstr("symbolic links")));
  EXPECT_THAT(ErrorOf([&] { ReadFileBytes(dir / std::string(300, 'n')); }), HasSubstr("too long"));
  std::ofstream(dir / "big.bin") << std::string(2000, 'x');
  EXPECT_THAT(ErrorOf([&] { ReadFileBytes(dir / "big.bin", 1024); }), HasSubstr("2000 bytes, more than the 1 KB"));
  std::filesystem::remove_all(dir);
}

TEST(FindFilesRecursively, FindsMatchingExtensionsInSubfoldersSorted) {
  const auto dir = dlslam::testing::MakeTempDir("find_files");
  std::filesystem::create_directories(dir / "b" / "deep");
  std::filesystem::create_directories(dir / "a");
  for (const char* name : {"b/deep/z.PNG", "a/y.jpg", "top.png", "notes.txt", "a/x.jpeg"}) {
    WriteBytes(dir / name, "x");
  }
  const auto files = FindFilesRecursively(dir, {".png", ".jpg"});
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0], dir / "a/y.jpg");
  EXPECT_EQ(files[1], dir / "b/deep/z.PNG");
  EXPECT_EQ(files[2], dir / "top.png");
  EXPECT_THAT(ErrorOf([&] { FindFilesRecursively(dir / "top.png", {".png"}); }), HasSubstr("not a folder"));
  std::filesystem::remove_all(dir);
}

TEST(FindModelFile, ExplicitPathMustExist) {
  const auto dir = dlslam::testing::MakeTempDir("model_file");
  WriteBytes(dir / "m.bin", "x");
  EXPECT_EQ(FindModelFile("whatever.bin", dir / "m.bin"), dir / "m.bin");
  EXPECT_THAT(ErrorOf([&] { FindModelFile("whatever.bin", dir / "missing.bin"); }),
              HasSubstr("missing.bin"));
  std::filesystem::remove_all(dir);
}

TEST(FindModelFile, FallsBackToTheSourceTreesModelsFolder) {
  // models/README.md is committed; tests do not run from an installed tree.
  const auto found = FindModelFile("README.md");
  EXPECT_TRUE(std::filesystem::equivalent(found, dlslam::testing::SourceDir() / "models" / "README.md"));
  const auto candidates = ModelFileCandidates("x.bin");
  ASSERT_EQ(candidates.size(), 2u);
  EXPECT_EQ(candidates[0].parent_path().filename(), "models");
  EXPECT_EQ(candidates[0].parent_path().parent_path().filename(), "dlslam");
  EXPECT_THAT(ErrorOf([] { FindModelFile("no_such_model.bin"); }),
              ::testing::AllOf(HasSubstr("no_such_model.bin"), HasSubstr("share/dlslam/models"),
                               HasSubstr("DLSLAM_MODEL_DIR")));
}

TEST(FindModelFile, ModelDirFromTheEnvironmentComesFirst) {
  const auto dir = dlslam::testing::MakeTempDir("model_dir_env");
  WriteBytes(dir / "README.md", "mine");
  ASSERT_EQ(setenv("DLSLAM_MODEL_DIR", dir.c_str(), 1), 0);
  const auto found = FindModelFile("README.md");
  const auto candidates = ModelFileCandidates("x.bin");
  unsetenv("DLSLAM_MODEL_DIR");
  EXPECT_EQ(found, dir / "README.md");
  ASSERT_EQ(candidates.size(), 3u);
  EXPECT_EQ(candidates[0], dir / "x.bin");
  // A folder given as the model is refused by name.
  EXPECT_THAT(ErrorOf([&] { FindModelFile("README.md", dir); }), HasSubstr("not a regular file"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace dlslam::io
