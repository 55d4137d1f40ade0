#include "dlslam/datasets/archive_extract.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "dlslam/datasets/fixture_archive.h"
#include "tests/support/test_data.h"

namespace dlslam::datasets {
namespace {

namespace fs = std::filesystem;
using testing::ArchiveFormat;
using testing::FixtureEntry;
using testing::MakeArchive;
using Type = FixtureEntry::Type;
using ::testing::HasSubstr;

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class ArchiveExtractTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = dlslam::testing::MakeTempDir("extract");
    dest_ = root_ / "dest";
    fs::create_directory(dest_);
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path Write(const std::string& bytes, const std::string& name = "a.tgz") {
    std::ofstream(root_ / name, std::ios::binary) << bytes;
    return root_ / name;
  }
  // Expects ExtractArchive to refuse with `message`, leaving nothing outside dest_.
  void ExpectRefused(const std::vector<FixtureEntry>& entries, const std::string& message) {
    const fs::path archive = Write(MakeArchive(entries, ArchiveFormat::kTgz));
    try {
      ExtractArchive(archive, dest_);
      FAIL() << "no error for " << message;
    } catch (const ArchiveContentError& e) {
      EXPECT_THAT(e.what(), HasSubstr(message));
      EXPECT_THAT(e.what(), HasSubstr(archive.string()));
    }
    EXPECT_FALSE(fs::exists(root_ / "evil.txt"));
    EXPECT_FALSE(fs::exists("/tmp/dlslam_extract_evil.txt"));
  }

  fs::path root_, dest_;
};

TEST_F(ArchiveExtractTest, TgzAndZipRoundTrip) {
  const auto entries = testing::TinySequence("seq");
  for (const ArchiveFormat format : {ArchiveFormat::kTgz, ArchiveFormat::kZip}) {
    fs::remove_all(dest_);
    fs::create_directory(dest_);
    const fs::path archive = Write(MakeArchive(entries, format));
    const ExtractStats stats = ExtractArchive(archive, dest_);
    EXPECT_EQ(stats.files, 7u);
    EXPECT_EQ(stats.directories, 3u);
    for (const FixtureEntry& e : entries) {
      if (e.type == Type::kFile) {
        EXPECT_EQ(ReadAll(dest_ / e.path), e.content) << e.path;
      }
      if (e.type == Type::kDirectory) {
        EXPECT_TRUE(fs::is_directory(dest_ / e.path)) << e.path;
      }
    }
  }
}

TEST_F(ArchiveExtractTest, InsideLinksAreKept) {
  const fs::path archive = Write(MakeArchive({{"seq/rgb.txt", "x"},
                                              {"seq/latest.txt", "rgb.txt", Type::kSymlink},
                                              {"seq/copy.txt", "seq/rgb.txt", Type::kHardlink},
                                              {"./seq/./dot.txt", "d"}},
                                             ArchiveFormat::kTgz));
  const ExtractStats stats = ExtractArchive(archive, dest_);
  EXPECT_EQ(stats.symlinks, 1u);
  EXPECT_TRUE(fs::is_symlink(dest_ / "seq/latest.txt"));
  EXPECT_EQ(ReadAll(dest_ / "seq/latest.txt"), "x");
  EXPECT_EQ(ReadAll(dest_ / "seq/copy.txt"), "x");
  EXPECT_EQ(ReadAll(dest_ / "seq/dot.txt"), "d");
}

TEST_F(ArchiveExtractTest, RefusesPathTraversal) {
  ExpectRefused({{"seq/rgb.txt", "ok"}, {"../evil.txt", "pwned"}}, "'..' leaves the target folder");
  ExpectRefused({{"seq/../../evil.txt", "pwned"}}, "'..' leaves the target folder");
  ExpectRefused({{"/tmp/dlslam_extract_evil.txt", "pwned"}}, "absolute path");
}

TEST_F(ArchiveExtractTest, RefusesLinksLeavingTheFolder) {
  ExpectRefused({{"seq/link", "../../evil.txt", Type::kSymlink}}, "points outside the target folder");
  ExpectRefused({{"seq/link", "/etc", Type::kSymlink}}, "points outside the target folder");
  ExpectRefused({{"link", "..", Type::kSymlink}}, "points outside the target folder");
  ExpectRefused({{"seq/hard", "../evil.txt", Type::kHardlink}}, "'..' leaves the target folder");
}

TEST_F(ArchiveExtractTest, CorruptOrForeignDataIsAContentError) {
  const std::string good = MakeArchive(testing::TinySequence("seq"), ArchiveFormat::kTgz);
  // Truncated in the middle of the compressed stream.
  EXPECT_THROW(ExtractArchive(Write(good.substr(0, good.size() / 2)), dest_), ArchiveContentError);
  // Not an archive at all.
  EXPECT_THROW(ExtractArchive(Write("<html>404 Not Found</html>", "b.tgz"), dest_), ArchiveContentError);
  // Damaged bytes inside the gzip stream (CRC / inflate error).
  std::string damaged = good;
  for (std::size_t i = 40; i < damaged.size() - 20; i += 7) damaged[i] = static_cast<char>(damaged[i] ^ 0x5a);
  EXPECT_THROW(ExtractArchive(Write(damaged, "c.tgz"), dest_), ArchiveContentError);
  EXPECT_THROW(ExtractArchive(root_ / "missing.tgz", dest_), ArchiveContentError);
}

TEST(SafeEntryPath, NormalizesAndRefuses) {
  EXPECT_EQ(SafeEntryPath("a", "./x/./y"), fs::path("x/y"));
  EXPECT_EQ(SafeEntryPath("a", "./"), fs::path());
  EXPECT_EQ(SafeEntryPath("a", "x/y/"), fs::path("x/y"));
  EXPECT_EQ(SafeEntryPath("a", "x..y/z"), fs::path("x..y/z"));  // ".." only as a whole component
  EXPECT_THROW(SafeEntryPath("a", ""), ArchiveContentError);
  EXPECT_THROW(SafeEntryPath("a", "x/../y"), ArchiveContentError);
  EXPECT_THROW(SafeEntryPath("a", "/x"), ArchiveContentError);
  EXPECT_THROW(SafeEntryPath("a", "\\x"), ArchiveContentError);
}

}  // namespace
}  // namespace dlslam::datasets
