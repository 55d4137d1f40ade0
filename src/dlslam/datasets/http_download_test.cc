#include "dlslam/datasets/http_download.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <curl/curl.h>

#include <fstream>
#include <sstream>

#include "tests/support/http_test_server.h"
#include "tests/support/test_data.h"

namespace dlslam::datasets {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class HttpDownloadTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = dlslam::testing::MakeTempDir("http_download");
    part_ = dir_ / "file.bin.part";
    for (int i = 0; i < 50000; ++i) body_ += static_cast<char>((i * 131) % 256);
    server_.Serve("/file.bin", body_);
    options_.show_progress = false;
    options_.retry_backoff_s = 0.001;
    options_.connect_timeout_s = 2;
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Url() const { return server_.BaseUrl() + "/file.bin"; }

  dlslam::testing::HttpTestServer server_;
  fs::path dir_, part_;
  std::string body_;
  DownloadOptions options_;
};

TEST_F(HttpDownloadTest, DownloadsWholeFileWithoutRange) {
  const DownloadResult r = DownloadToFile(Url(), part_, options_);
  EXPECT_EQ(ReadAll(part_), body_);
  EXPECT_EQ(r.size_bytes, body_.size());
  EXPECT_TRUE(r.size_verified);
  EXPECT_EQ(r.resumed_from, 0u);
  ASSERT_EQ(server_.Requests().size(), 1u);
  EXPECT_EQ(server_.Requests()[0].method, "GET");
  EXPECT_EQ(server_.Requests()[0].range, "");
}

TEST_F(HttpDownloadTest, ResumesFromPartialFile) {
  std::ofstream(part_, std::ios::binary) << body_.substr(0, 12345);
  const DownloadResult r = DownloadToFile(Url(), part_, options_);
  EXPECT_EQ(ReadAll(part_), body_);
  EXPECT_EQ(r.resumed_from, 12345u);
  EXPECT_EQ(r.received_bytes, body_.size() - 12345);
  ASSERT_EQ(server_.Requests().size(), 1u);
  EXPECT_EQ(server_.Requests()[0].range, "bytes=12345-");
}

TEST_F(HttpDownloadTest, CutConnectionIsRetriedWithARange) {
  server_.CutAfter(20000, 2);
  const DownloadResult r = DownloadToFile(Url(), part_, options_);
  EXPECT_EQ(ReadAll(part_), body_);
  EXPECT_EQ(r.attempts, 3);
  const auto requests = server_.Requests();
  ASSERT_EQ(requests.size(), 3u);
  EXPECT_EQ(requests[0].range, "");
  EXPECT_EQ(requests[1].range, "bytes=20000-");
  EXPECT_EQ(requests[2].range, "bytes=40000-");
}

TEST_F(HttpDownloadTest, GivesUpAfterTheRetriesAndKeepsThePart) {
  server_.CutAfter(1000, 10);
  options_.max_retries = 2;
  try {
    DownloadToFile(Url(), part_, options_);
    FAIL();
  } catch (const DownloadError& e) {
    EXPECT_THAT(e.what(), HasSubstr("after 3 attempts"));
    EXPECT_THAT(e.what(), HasSubstr(Url()));
  }
  EXPECT_EQ(fs::file_size(part_), 3000u);  // kept for the next run
  EXPECT_EQ(ReadAll(part_), body_.substr(0, 3000));
}

TEST_F(HttpDownloadTest, ServerIgnoringRangeRestartsCleanly) {
  server_.IgnoreRange(true);
  std::ofstream(part_, std::ios::binary) << std::string(7000, 'Z');  // junk that must not survive
  const DownloadResult r = DownloadToFile(Url(), part_, options_);
  EXPECT_EQ(ReadAll(part_), body_);
  EXPECT_EQ(r.resumed_from, 0u);
  ASSERT_EQ(server_.Requests().size(), 1u);
  EXPECT_EQ(server_.Requests()[0].range, "bytes=7000-");
}

TEST_F(HttpDownloadTest, CompletePartAnswered416IsDone) {
  std::ofstream(part_, std::ios::binary) << body_;
  const DownloadResult r = DownloadToFile(Url(), part_, options_);
  EXPECT_EQ(ReadAll(part_), body_);
  EXPECT_TRUE(r.size_verified);
  EXPECT_EQ(r.received_bytes, 0u);
}

TEST_F(HttpDownloadTest, OversizedPartStartsOver) {
  std::ofstream(part_, std::ios::binary) << body_ << "extra";
  DownloadToFile(Url(), part_, options_);
  EXPECT_EQ(ReadAll(part_), body_);
  ASSERT_EQ(server_.Requests().size(), 2u);  // 416, then a plain GET
  EXPECT_EQ(server_.Requests()[1].range, "");
}

TEST_F(HttpDownloadTest, NotFoundNamesTheUrlAndIsNotRetried) {
  const std::string url = server_.BaseUrl() + "/missing.tgz";
  try {
    DownloadToFile(url, part_, options_);
    FAIL();
  } catch (const DownloadError& e) {
    EXPECT_THAT(e.what(), HasSubstr("HTTP 404 Not Found for " + url));
  }
  EXPECT_EQ(server_.Requests().size(), 1u);
  EXPECT_FALSE(fs::exists(part_));
}

TEST_F(HttpDownloadTest, ServerErrorsAreRetried) {
  server_.FailNext(503, 2);
  const DownloadResult r = DownloadToFile(Url(), part_, options_);
  EXPECT_EQ(ReadAll(part_), body_);
  EXPECT_EQ(r.attempts, 3);
}

TEST_F(HttpDownloadTest, FollowsRedirects) {
  server_.Redirect("/old/file.bin", "/file.bin");
  DownloadToFile(server_.BaseUrl() + "/old/file.bin", part_, options_);
  EXPECT_EQ(ReadAll(part_), body_);
  EXPECT_EQ(server_.Requests().size(), 2u);
}

TEST_F(HttpDownloadTest, WrongExpectedSizeIsAnError) {
  options_.expected_size = body_.size() + 1;
  EXPECT_THROW(DownloadToFile(Url(), part_, options_), DownloadError);
  EXPECT_FALSE(fs::exists(part_));
}

TEST_F(HttpDownloadTest, NoServerGivesCurlsMessage) {
  options_.max_retries = 0;
  // Port 1 on the loopback: nothing listens there, the connection is refused at once.
  try {
    DownloadToFile("http://127.0.0.1:1/x.tgz", part_, options_);
    FAIL();
  } catch (const DownloadError& e) {
    EXPECT_THAT(e.what(), HasSubstr("http://127.0.0.1:1/x.tgz"));
    EXPECT_THAT(e.what(), HasSubstr("Couldn't connect to server"));
  }
}

TEST_F(HttpDownloadTest, RejectsBadOptions) {
  options_.max_retries = -1;
  EXPECT_THROW(DownloadToFile(Url(), part_, options_), Error);
  EXPECT_TRUE(server_.Requests().empty());
}

// The loopback server itself: HEAD answers the size without a body.
TEST(HttpTestServer, HeadSendsHeadersOnly) {
  dlslam::testing::HttpTestServer server;
  server.Serve("/a.bin", std::string(1234, 'a'));
  CURL* curl = curl_easy_init();
  ASSERT_NE(curl, nullptr);
  std::string url = server.BaseUrl() + "/a.bin";
  std::string received;
  curl_easy_setopt(curl, CURLOPT_URL, url.c_str());
  curl_easy_setopt(curl, CURLOPT_NOBODY, 1L);
  curl_easy_setopt(curl, CURLOPT_NOSIGNAL, 1L);
  EXPECT_EQ(curl_easy_perform(curl), CURLE_OK);
  long status = 0;
  curl_off_t length = -1;
  curl_easy_getinfo(curl, CURLINFO_RESPONSE_CODE, &status);
  curl_easy_getinfo(curl, CURLINFO_CONTENT_LENGTH_DOWNLOAD_T, &length);
  curl_easy_cleanup(curl);
  EXPECT_EQ(status, 200);
  EXPECT_EQ(length, 1234);
  ASSERT_EQ(server.Requests().size(), 1u);
  EXPECT_EQ(server.Requests()[0].method, "HEAD");
}

}  // namespace
}  // namespace dlslam::datasets
