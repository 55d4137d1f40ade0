#pragma once
// A tiny HTTP/1.1 server on 127.0.0.1 (ephemeral port) for tests that must
// not touch the internet. One thread, one connection at a time, and every
// response closes its connection. It serves GET and HEAD of registered
// bodies, "Range: bytes=N-" / "bytes=N-M" (206, 416), 404 for anything else,
// 302 redirects, and on request misbehaves: cuts a body after K bytes,
// ignores Range (answers 200), or answers an error status a few times.
//
//   HttpTestServer server;
//   server.Serve("/a.tgz", bytes);
//   server.CutAfter(1000);            // the next GET body stops after 1000 bytes
//   Download(server.BaseUrl() + "/a.tgz");
//   server.Requests()[1].range        // "bytes=1000-"

#include <cstddef>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace dlslam::testing {

class HttpTestServer {
 public:
  struct Request {
    std::string method;  // "GET", "HEAD", ...
    std::string path;    // "/a.tgz"
    std::string range;   // the Range header's value, "" when absent
  };

  HttpTestServer();   // listening when it returns; throws std::runtime_error on socket errors
  ~HttpTestServer();  // stops the thread and joins it
  HttpTestServer(const HttpTestServer&) = delete;
  HttpTestServer& operator=(const HttpTestServer&) = delete;

  std::string BaseUrl() const;  // "http://127.0.0.1:<port>"

  void Serve(const std::string& path, std::string body);
  void Redirect(const std::string& from, const std::string& to);  // 302 to a path on this server
  // The next `times` GET bodies send only `bytes` bytes, then close the connection.
  void CutAfter(std::size_t bytes, int times = 1);
  // Answer 200 with the whole body even when a Range was asked for.
  void IgnoreRange(bool ignore);
  // The next `times` requests get `status` with a short body.
  void FailNext(int status, int times = 1);

  std::vector<Request> Requests() const;

 private:
  void Run();
  void Handle(int fd);

  int listen_fd_ = -1;
  int wake_pipe_[2] = {-1, -1};
  int port_ = 0;
  std::thread thread_;

  mutable std::mutex mutex_;  // guards everything below
  std::map<std::string, std::string> bodies_;
  std::map<std::string, std::string> redirects_;
  std::size_t cut_bytes_ = 0;
  int cut_times_ = 0;
  bool ignore_range_ = false;
  int fail_status_ = 0;
  int fail_times_ = 0;
  std::vector<Request> requests_;
};

}  // namespace dlslam::testing
