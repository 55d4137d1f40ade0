#include "dlslam/datasets/http_download.h"

#include <curl/curl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <system_error>
#include <thread>

#include "dlslam/datasets/progress_bar.h"

namespace dlslam::datasets {
namespace {

namespace fs = std::filesystem;

std::optional<std::uint64_t> ParseUint(std::string_view text) {
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end == text.data()) return std::nullopt;
  return value;
}

std::string_view Trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

bool StartsWithNoCase(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() &&
         std::equal(prefix.begin(), prefix.end(), s.begin(),
                    [](char a, char b) { return std::tolower(a) == std::tolower(b); });
}

// What one request learned and did. Headers are reset at every status line,
// so after redirects they describe the final response.
struct Attempt {
  fs::path path;
  std::uint64_t offset = 0;  // bytes already in the file when the request was sent
  long status = 0;
  std::optional<std::uint64_t> content_length;
  std::optional<std::uint64_t> range_start, range_total;  // Content-Range: bytes a-b/t or */t
  std::FILE* file = nullptr;
  bool body_started = false;
  bool restarted = false;  // server ignored the Range and sent the whole file
  std::string write_error;
  std::uint64_t received = 0;
  ProgressBar* progress = nullptr;

  std::uint64_t start() const { return restarted ? 0 : offset; }
  std::optional<std::uint64_t> Total() const {
    if (status == 206) return range_total;
    if (content_length) return *content_length + (status == 200 ? 0 : offset);
    return std::nullopt;
  }
};

std::size_t OnHeader(char* data, std::size_t size, std::size_t count, void* user) {
  auto& a = *static_cast<Attempt*>(user);
  const std::string_view line = Trim(std::string_view(data, size * count));
  if (StartsWithNoCase(line, "HTTP/")) {
    const auto space = line.find(' ');
    a.status = space == std::string_view::npos
                   ? 0
                   : static_cast<long>(ParseUint(line.substr(space + 1, 3)).value_or(0));
    a.content_length.reset();
    a.range_start.reset();
    a.range_total.reset();
  } else if (StartsWithNoCase(line, "content-length:")) {
    a.content_length = ParseUint(Trim(line.substr(15)));
  } else if (StartsWithNoCase(line, "content-range:")) {
    std::string_view value = Trim(line.substr(14));
    if (StartsWithNoCase(value, "bytes")) value = Trim(value.substr(5));
    const auto slash = value.find('/');
    if (slash != std::string_view::npos) {
      a.range_total = ParseUint(value.substr(slash + 1));
      if (value[0] != '*') a.range_start = ParseUint(value.substr(0, value.find('-')));
    }
  }
  return size * count;
}

std::size_t OnBody(char* data, std::size_t size, std::size_t count, void* user) {
  auto& a = *static_cast<Attempt*>(user);
  const std::size_t bytes = size * count;
  if (a.status != 200 && a.status != 206) return bytes;  // an error page: not ours to keep
  if (!a.body_started) {
    a.body_started = true;
    if (a.status == 206 && a.range_start != a.offset) {
      a.write_error = fmt::format("server sent a range starting at {} instead of {}",
                                  a.range_start.value_or(0), a.offset);
      return 0;
    }
    a.restarted = a.status == 200 && a.offset > 0;
    if (a.restarted) spdlog::warn("server ignored the range request; downloading from the start");
    a.file = std::fopen(a.path.c_str(), a.status == 206 ? "ab" : "wb");
    if (a.file == nullptr) {
      a.write_error = fmt::format("cannot open '{}' for writing", a.path.string());
      return 0;
    }
  }
  if (std::fwrite(data, 1, bytes, a.file) != bytes) {
    a.write_error = fmt::format("cannot write '{}' (disk full?)", a.path.string());
    return 0;
  }
  a.received += bytes;
  return bytes;
}

int OnProgress(void* user, curl_off_t /*dltotal*/, curl_off_t /*dlnow*/, curl_off_t, curl_off_t) {
  const auto& a = *static_cast<Attempt*>(user);
  if (a.body_started && a.write_error.empty()) {
    a.progress->Update(a.start() + a.received, a.Total().value_or(0), a.start());
  }
  return 0;
}

// Failures that another attempt will not fix.
bool IsPermanent(CURLcode code) {
  switch (code) {
    case CURLE_UNSUPPORTED_PROTOCOL: case CURLE_URL_MALFORMAT: case CURLE_COULDNT_RESOLVE_PROXY:
    case CURLE_COULDNT_RESOLVE_HOST: case CURLE_PEER_FAILED_VERIFICATION: case CURLE_TOO_MANY_REDIRECTS:
    case CURLE_SSL_CERTPROBLEM: case CURLE_SSL_CACERT_BADFILE: case CURLE_FILESIZE_EXCEEDED:
      return true;
    default:
      return false;
  }
}

std::uint64_t FileSize(const fs::path& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  return ec ? 0 : size;
}

struct CurlDeleter {
  void operator()(CURL* curl) const { curl_easy_cleanup(curl); }
};

// One HTTP request. Returns true when the file is complete; false when a
// retry may help (`why` says what happened); throws when it will not.
bool RunAttempt(const std::string& url, Attempt& a, const DownloadOptions& options, std::string& why) {
  static std::once_flag global_init;
  std::call_once(global_init, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
  std::unique_ptr<CURL, CurlDeleter> curl(curl_easy_init());
  if (!curl) throw DownloadError("libcurl failed to initialise");
  char error_buffer[CURL_ERROR_SIZE] = "";
  const std::string range = fmt::format("{}-", a.offset);
  CURL* c = curl.get();
  curl_easy_setopt(c, CURLOPT_URL, url.c_str());
  curl_easy_setopt(c, CURLOPT_ERRORBUFFER, error_buffer);
  curl_easy_setopt(c, CURLOPT_NOSIGNAL, 1L);  // no SIGALRM: safe in threads
  curl_easy_setopt(c, CURLOPT_FOLLOWLOCATION, 1L);
  curl_easy_setopt(c, CURLOPT_MAXREDIRS, 10L);
  curl_easy_setopt(c, CURLOPT_PROTOCOLS_STR, "http,https");
  curl_easy_setopt(c, CURLOPT_REDIR_PROTOCOLS_STR, "http,https");
  curl_easy_setopt(c, CURLOPT_USERAGENT, "dlslam-dataset-fetch/0.1");
  curl_easy_setopt(c, CURLOPT_CONNECTTIMEOUT_MS, std::lround(options.connect_timeout_s * 1000));
  curl_easy_setopt(c, CURLOPT_LOW_SPEED_LIMIT, 1024L);
  curl_easy_setopt(c, CURLOPT_LOW_SPEED_TIME, std::max(1L, std::lround(options.stall_timeout_s)));
  // CURLOPT_RANGE rather than CURLOPT_RESUME_FROM: libcurl then leaves a 200
  // answer to us (restart) instead of failing the transfer.
  if (a.offset > 0) curl_easy_setopt(c, CURLOPT_RANGE, range.c_str());
  curl_easy_setopt(c, CURLOPT_HEADERFUNCTION, OnHeader);
  curl_easy_setopt(c, CURLOPT_HEADERDATA, &a);
  curl_easy_setopt(c, CURLOPT_WRITEFUNCTION, OnBody);
  curl_easy_setopt(c, CURLOPT_WRITEDATA, &a);
  curl_easy_setopt(c, CURLOPT_XFERINFOFUNCTION, OnProgress);
  curl_easy_setopt(c, CURLOPT_XFERINFODATA, &a);
  curl_easy_setopt(c, CURLOPT_NOPROGRESS, 0L);

  const CURLcode code = curl_easy_perform(c);
  if (a.file != nullptr && std::fclose(a.file) != 0 && a.write_error.empty()) {
    a.write_error = fmt::format("cannot write '{}' (disk full?)", a.path.string());
  }
  a.file = nullptr;
  if (!a.write_error.empty()) {
    if (a.body_started && a.status == 206 && a.range_start != a.offset) {
      fs::remove(a.path);  // inconsistent resume: start over
      why = a.write_error;
      return false;
    }
    throw DownloadError(fmt::format("{}: {}", url, a.write_error));
  }
  if (code != CURLE_OK) {
    why = fmt::format("{} ({})", error_buffer[0] != '\0' ? error_buffer : curl_easy_strerror(code),
                      curl_easy_strerror(code));
    if (IsPermanent(code)) throw DownloadError(fmt::format("cannot download {}: {}", url, why));
    return false;
  }
  if (a.status == 416) {
    // Nothing left to send: complete if the server's total is what we have.
    if (a.range_total && *a.range_total == a.offset) return true;
    fs::remove(a.path);
    why = "server rejected the resume range; starting over";
    return false;
  }
  if (a.status == 429 || a.status >= 500) {
    why = fmt::format("HTTP {}", a.status);
    return false;
  }
  if (a.status != 200 && a.status != 206) {
    throw DownloadError(fmt::format("HTTP {}{} for {}", a.status, a.status == 404 ? " Not Found" : "", url));
  }
  if (!a.body_started && a.status == 200) {  // an empty file: nothing came to truncate it
    if (std::FILE* empty = std::fopen(a.path.c_str(), "wb")) std::fclose(empty);
  }
  const auto total = a.Total();
  if (total && FileSize(a.path) < *total) {
    why = fmt::format("connection closed after {} of {} bytes", FileSize(a.path), *total);
    return false;
  }
  return true;
}

}  // namespace

void DownloadOptions::Check() const {
  DLSLAM_CHECK(connect_timeout_s > 0 && std::isfinite(connect_timeout_s),
               "connect_timeout_s must be positive, got {}", connect_timeout_s);
  DLSLAM_CHECK(stall_timeout_s > 0 && std::isfinite(stall_timeout_s),
               "stall_timeout_s must be positive, got {}", stall_timeout_s);
  DLSLAM_CHECK(max_retries >= 0 && max_retries <= 100, "max_retries must be in [0, 100], got {}",
               max_retries);
  DLSLAM_CHECK(retry_backoff_s >= 0 && retry_backoff_s <= 600, "retry_backoff_s must be in [0, 600], got {}",
               retry_backoff_s);
}

DownloadResult DownloadToFile(const std::string& url, const fs::path& part, const DownloadOptions& options) {
  options.Check();
  DownloadResult result;
  ProgressBar progress(part.stem().string(), options.show_progress);  // "x.tgz" for "x.tgz.part"
  if (options.expected_size > 0 && FileSize(part) > options.expected_size) fs::remove(part);
  bool first = true;
  std::optional<std::uint64_t> total;
  for (int retry = 0;; ++retry) {
    Attempt a;
    a.path = part;
    a.offset = FileSize(part);
    a.progress = &progress;
    if (first) result.resumed_from = a.offset;
    first = false;
    std::string why;
    ++result.attempts;
    const bool done = RunAttempt(url, a, options, why);
    if (a.restarted) result.resumed_from = 0;
    result.received_bytes += a.received;
    // Only answers carrying the file tell its size (not error pages or redirects).
    if ((a.status == 200 || a.status == 206) && a.Total()) total = a.Total();
    if (a.status == 416 && done) total = a.range_total;
    if (done) break;
    progress.Finish();
    if (retry >= options.max_retries) {
      throw DownloadError(fmt::format("cannot download {} after {} attempts: {}", url, result.attempts, why));
    }
    const double wait_s = options.retry_backoff_s * std::pow(2.0, retry);
    spdlog::warn("download interrupted: {}; retrying in {:.1f} s", why, wait_s);
    std::this_thread::sleep_for(std::chrono::duration<double>(wait_s));
  }
  progress.Finish();
  result.size_bytes = FileSize(part);
  if (total && *total != result.size_bytes) {
    throw DownloadError(fmt::format("{}: got {} bytes, the server announced {}", url, result.size_bytes, *total));
  }
  result.size_verified = total.has_value();
  if (options.expected_size > 0 && result.size_bytes != options.expected_size) {
    fs::remove(part);
    throw DownloadError(fmt::format("{}: got {} bytes, expected {}; removed the download", url,
                                    result.size_bytes, options.expected_size));
  }
  return result;
}

}  // namespace dlslam::datasets
