#include "dlslam/datasets/fetch.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "dlslam/datasets/digest.h"
#include "dlslam/datasets/fixture_archive.h"
#include "tests/support/http_test_server.h"
#include "tests/support/test_data.h"

namespace dlslam::datasets {
namespace {

namespace fs = std::filesystem;
using testing::ArchiveFormat;
using testing::FixtureEntry;
using ::testing::HasSubstr;

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

constexpr const char* kName = "rgbd_dataset_freiburg3_walking_xyz";
constexpr const char* kServerPath = "/freiburg3/rgbd_dataset_freiburg3_walking_xyz.tgz";

class FetchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = dlslam::testing::MakeTempDir("fetch");
    entries_ = testing::TinySequence(kName);
    archive_ = testing::MakeArchive(entries_, ArchiveFormat::kTgz);
    server_.Serve(kServerPath, archive_);
    options_.dir = dir_ / "data";
    options_.base_url = server_.BaseUrl();
    options_.download.show_progress = false;
    options_.download.retry_backoff_s = 0.001;
  }
  void TearDown() override { fs::remove_all(dir_); }

  FetchResult Fetch() { return FetchSequence(FindSequence("fr3/walking_xyz"), options_); }
  void ExpectSequenceUnpacked() const {
    for (const FixtureEntry& e : entries_) {
      if (e.type == FixtureEntry::Type::kFile) {
        EXPECT_EQ(ReadAll(options_.dir / e.path), e.content) << e.path;
      }
    }
  }
  // After a failure: no sequence folder, no staging, no lock; only a .part may stay.
  void ExpectNothingLooksComplete() const {
    EXPECT_FALSE(fs::exists(options_.dir / kName));
    if (!fs::exists(options_.dir)) return;
    for (const auto& entry : fs::directory_iterator(options_.dir)) {
      EXPECT_TRUE(entry.path().extension() == ".part") << "left behind: " << entry.path();
    }
  }

  dlslam::testing::HttpTestServer server_;
  fs::path dir_;
  std::vector<FixtureEntry> entries_;
  std::string archive_;
  FetchOptions options_;
};

TEST_F(FetchTest, DownloadsVerifiesAndUnpacks) {
  const FetchResult r = Fetch();
  EXPECT_EQ(r.sequence_dir, options_.dir / kName);
  EXPECT_FALSE(r.already_present);
  EXPECT_TRUE(r.download.size_verified);
  EXPECT_EQ(r.download.size_bytes, archive_.size());
  EXPECT_EQ(r.sha256, DigestHex(archive_, DigestKind::kSha256));
  EXPECT_EQ(r.extracted.files, 7u);
  ExpectSequenceUnpacked();
  EXPECT_TRUE(LooksLikeCompleteSequence(r.sequence_dir));
  EXPECT_THAT(ReadAll(r.sequence_dir / kFetchStampName), HasSubstr(server_.BaseUrl() + kServerPath));
  // Only the sequence is left: archive, .part, staging and lock are gone.
  std::vector<fs::path> left;
  for (const auto& entry : fs::directory_iterator(options_.dir)) left.push_back(entry.path().filename());
  EXPECT_EQ(left, std::vector<fs::path>{kName});
}

TEST_F(FetchTest, KeepArchiveAndReuseItLater) {
  options_.keep_archive = true;
  Fetch();
  const fs::path archive = options_.dir / (std::string(kName) + ".tgz");
  EXPECT_EQ(ReadAll(archive), archive_);
  fs::remove_all(options_.dir / kName);
  const FetchResult again = Fetch();
  EXPECT_TRUE(again.reused_archive);
  EXPECT_EQ(server_.Requests().size(), 1u);  // the second run made no request
  ExpectSequenceUnpacked();
}

TEST_F(FetchTest, BonnZipUnpacks) {
  const auto entries = testing::TinySequence("rgbd_bonn_crowd");
  server_.Serve("/rgbd_bonn_crowd.zip", testing::MakeArchive(entries, ArchiveFormat::kZip));
  const FetchResult r = FetchSequence(FindSequence("bonn/crowd"), options_);
  EXPECT_EQ(ReadAll(r.sequence_dir / "rgb.txt"), entries[1].content);
  EXPECT_EQ(ReadAll(r.sequence_dir / "depth/1305031102.194330.png"), entries.back().content);
}

TEST_F(FetchTest, InterruptedDownloadResumesOnTheNextRun) {
  server_.CutAfter(archive_.size() / 2);
  options_.download.max_retries = 0;
  EXPECT_THROW(Fetch(), DownloadError);
  ExpectNothingLooksComplete();
  const fs::path part = options_.dir / (std::string(kName) + ".tgz.part");
  ASSERT_EQ(fs::file_size(part), archive_.size() / 2);

  const FetchResult r = Fetch();
  EXPECT_EQ(r.download.resumed_from, archive_.size() / 2);
  const auto requests = server_.Requests();
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_EQ(requests[1].range, "bytes=" + std::to_string(archive_.size() / 2) + "-");
  ExpectSequenceUnpacked();
  EXPECT_FALSE(fs::exists(part));
}

TEST_F(FetchTest, ServerIgnoringRangeStillGivesTheRightFiles) {
  const fs::path part = options_.dir / (std::string(kName) + ".tgz.part");
  fs::create_directories(options_.dir);
  std::ofstream(part, std::ios::binary) << std::string(100, '\0');  // not a prefix of the archive
  server_.IgnoreRange(true);
  const FetchResult r = Fetch();
  EXPECT_EQ(server_.Requests().at(0).range, "bytes=100-");
  EXPECT_EQ(r.download.resumed_from, 0u);
  ExpectSequenceUnpacked();
}

TEST_F(FetchTest, ChecksumsAreVerified) {
  options_.sha256 = DigestHex(archive_, DigestKind::kSha256);
  options_.md5 = DigestHex(archive_, DigestKind::kMd5);
  Fetch();
  ExpectSequenceUnpacked();
}

TEST_F(FetchTest, ChecksumMismatchLeavesNoSequence) {
  for (const bool use_md5 : {false, true}) {
    options_.sha256 = use_md5 ? "" : std::string(64, '0');
    options_.md5 = use_md5 ? std::string(32, 'a') : "";
    try {
      Fetch();
      FAIL();
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(use_md5 ? "md5 mismatch" : "sha256 mismatch"));
      EXPECT_THAT(e.what(), HasSubstr(use_md5 ? std::string(32, 'a') : std::string(64, '0')));
    }
    ExpectNothingLooksComplete();
    EXPECT_FALSE(fs::exists(options_.dir / (std::string(kName) + ".tgz.part")));
  }
}

TEST_F(FetchTest, CorruptArchiveLeavesNothingThatLooksComplete) {
  // A big incompressible file in the middle, so the cut lands inside its data
  // after the small files before it were already written to the staging folder.
  auto entries = entries_;
  std::mt19937 random(7);
  std::string noise(200000, '\0');
  for (char& c : noise) c = static_cast<char>(random());
  entries.insert(entries.begin() + 5, {std::string(kName) + "/rgb/big.png", noise});
  const std::string whole = testing::MakeArchive(entries, ArchiveFormat::kTgz);
  for (const std::size_t keep : {whole.size() * 3 / 5, whole.size() / 20}) {
    server_.Serve(kServerPath, whole.substr(0, keep));
    try {
      Fetch();
      FAIL();
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("corrupt"));
      EXPECT_THAT(e.what(), HasSubstr("removed the archive"));
      // The long cut fails inside big.png, the short one before the first entry.
      if (keep > whole.size() / 2) {
        EXPECT_THAT(e.what(), HasSubstr("rgb/big.png"));
      }
    }
    ExpectNothingLooksComplete();
  }
}

TEST_F(FetchTest, PathTraversalIsRefused) {
  auto entries = entries_;
  entries.push_back({std::string(kName) + "/../../evil.txt", "pwned"});
  server_.Serve(kServerPath, testing::MakeArchive(entries, ArchiveFormat::kTgz));
  try {
    Fetch();
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("refusing entry"));
  }
  ExpectNothingLooksComplete();
  EXPECT_FALSE(fs::exists(dir_ / "evil.txt"));
  EXPECT_FALSE(fs::exists(options_.dir / "evil.txt"));
}

TEST_F(FetchTest, NotFoundNamesTheUrl) {
  options_.base_url = server_.BaseUrl() + "/no-such-mirror";
  try {
    Fetch();
    FAIL();
  } catch (const DownloadError& e) {
    EXPECT_THAT(e.what(), HasSubstr("404"));
    EXPECT_THAT(e.what(), HasSubstr(server_.BaseUrl() + "/no-such-mirror" + kServerPath));
  }
  ExpectNothingLooksComplete();
}

TEST_F(FetchTest, AlreadyPresentMakesNoRequest) {
  fs::create_directories(options_.dir / kName);
  std::ofstream(options_.dir / kName / "rgb.txt") << "# unpacked by hand\n";
  std::ofstream(options_.dir / kName / "depth.txt") << "# unpacked by hand\n";
  EXPECT_TRUE(Fetch().already_present);
  EXPECT_TRUE(server_.Requests().empty());
}

TEST_F(FetchTest, IncompleteFolderIsNotOverwritten) {
  fs::create_directories(options_.dir / kName / "rgb");
  try {
    Fetch();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("does not look like a complete sequence"));
  }
  EXPECT_TRUE(fs::is_directory(options_.dir / kName / "rgb"));
  EXPECT_TRUE(server_.Requests().empty());
}

TEST_F(FetchTest, LeftoverStagingIsReplaced) {
  const fs::path staging = options_.dir / ("." + std::string(kName) + ".staging");
  fs::create_directories(staging / kName);
  std::ofstream(staging / kName / "half.png") << "interrupted";
  Fetch();
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_FALSE(fs::exists(options_.dir / kName / "half.png"));
  ExpectSequenceUnpacked();
}

TEST_F(FetchTest, ArchiveWithoutTopFolderBecomesTheSequence) {
  server_.Serve(kServerPath, testing::MakeArchive({{"rgb.txt", "r"}, {"depth.txt", "d"}}, ArchiveFormat::kTgz));
  const FetchResult r = Fetch();
  EXPECT_EQ(ReadAll(r.sequence_dir / "rgb.txt"), "r");
  EXPECT_EQ(ReadAll(r.sequence_dir / "depth.txt"), "d");
}

TEST_F(FetchTest, RejectsBadOptions) {
  options_.sha256 = "xyz";
  EXPECT_THROW(Fetch(), Error);
  options_.sha256.clear();
  options_.base_url = "ftp://example.org";
  EXPECT_THROW(Fetch(), Error);
  EXPECT_TRUE(server_.Requests().empty());
}

}  // namespace
}  // namespace dlslam::datasets
