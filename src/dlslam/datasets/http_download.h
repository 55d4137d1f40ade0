#pragma once
// Resumable HTTP(S) download of one file with libcurl.
//
//   DownloadResult r = DownloadToFile(url, dir / "x.tgz.part", options);
//
// The bytes go to `part`. When `part` already holds N bytes, the request
// asks for "Range: bytes=N-" and appends; a server that answers 200 (range
// ignored) restarts the file from byte 0. Transient failures (connection
// lost, timeouts, HTTP 5xx) are retried with exponential back-off, each retry
// resuming where the last one stopped. The final size is checked against the
// server's total (Content-Length / Content-Range) and options.expected_size.

#include <cstdint>
#include <filesystem>
#include <string>

#include "dlslam/util/check.h"

namespace dlslam::datasets {

struct DownloadOptions {
  double connect_timeout_s = 20.0;  // s; time allowed to open a connection
  // s; an attempt whose speed stays below 1 KiB/s this long is aborted (and retried).
  double stall_timeout_s = 60.0;
  int max_retries = 4;           // retries after a transient failure (attempts = 1 + this)
  double retry_backoff_s = 1.0;  // s; wait before the first retry, doubled for each next one
  bool show_progress = true;     // progress bar on stderr (drawn only when stderr is a TTY)
  std::uint64_t expected_size = 0;  // bytes; the size the file must have, 0 = not known

  // Throws dlslam::Error naming the bad field and its value.
  void Check() const;
};

struct DownloadResult {
  std::uint64_t size_bytes = 0;    // size of the complete file
  std::uint64_t resumed_from = 0;  // bytes of an earlier .part the server let us keep
  std::uint64_t received_bytes = 0;  // body bytes written by this call
  bool size_verified = false;  // the server stated the total size and the file matches it
  int attempts = 0;            // HTTP requests made
};

// Thrown when the download cannot complete: HTTP 4xx, no connection after the
// retries, size mismatch, or the local file cannot be written. The message
// names the URL.
class DownloadError : public Error {
 public:
  using Error::Error;
};

DownloadResult DownloadToFile(const std::string& url, const std::filesystem::path& part,
                              const DownloadOptions& options);

}  // namespace dlslam::datasets
