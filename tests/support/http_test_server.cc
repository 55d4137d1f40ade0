#include "tests/support/http_test_server.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace dlslam::testing {
namespace {

[[noreturn]] void Fail(const std::string& what) {
  throw std::runtime_error("HttpTestServer: " + what + ": " + std::strerror(errno));
}

void SendAll(int fd, const std::string& data) {
  std::size_t sent = 0;
  while (sent < data.size()) {
    const ssize_t n = ::send(fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;  // the client went away: nothing to do
    sent += static_cast<std::size_t>(n);
  }
}

// Reads up to the blank line ending the request head; "" on timeout or close.
std::string ReadHead(int fd) {
  std::string head;
  char buffer[4096];
  while (head.find("\r\n\r\n") == std::string::npos && head.size() < 65536) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 5000) <= 0) return "";
    const ssize_t n = ::recv(fd, buffer, sizeof(buffer), 0);
    if (n <= 0) return "";
    head.append(buffer, static_cast<std::size_t>(n));
  }
  return head;
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string StatusLine(int status) {
  const char* reason = status == 200   ? "OK"
                       : status == 206 ? "Partial Content"
                       : status == 302 ? "Found"
                       : status == 404 ? "Not Found"
                       : status == 416 ? "Range Not Satisfiable"
                                       : "Error";
  return "HTTP/1.1 " + std::to_string(status) + " " + reason + "\r\n";
}

}  // namespace

HttpTestServer::HttpTestServer() {
  listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0) Fail("socket");
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;  // ephemeral
  if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) Fail("bind");
  if (::listen(listen_fd_, 16) != 0) Fail("listen");
  socklen_t length = sizeof(address);
  if (::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&address), &length) != 0) Fail("getsockname");
  port_ = ntohs(address.sin_port);
  if (::pipe2(wake_pipe_, O_CLOEXEC) != 0) Fail("pipe");
  thread_ = std::thread([this] { Run(); });
}

HttpTestServer::~HttpTestServer() {
  const char stop = 'x';
  [[maybe_unused]] const ssize_t n = ::write(wake_pipe_[1], &stop, 1);
  thread_.join();
  ::close(listen_fd_);
  ::close(wake_pipe_[0]);
  ::close(wake_pipe_[1]);
}

std::string HttpTestServer::BaseUrl() const { return "http://127.0.0.1:" + std::to_string(port_); }

void HttpTestServer::Serve(const std::string& path, std::string body) {
  const std::lock_guard lock(mutex_);
  bodies_[path] = std::move(body);
}

void HttpTestServer::Redirect(const std::string& from, const std::string& to) {
  const std::lock_guard lock(mutex_);
  redirects_[from] = to;
}

void HttpTestServer::CutAfter(std::size_t bytes, int times) {
  const std::lock_guard lock(mutex_);
  cut_bytes_ = bytes;
  cut_times_ = times;
}

void HttpTestServer::IgnoreRange(bool ignore) {
  const std::lock_guard lock(mutex_);
  ignore_range_ = ignore;
}

void HttpTestServer::FailNext(int status, int times) {
  const std::lock_guard lock(mutex_);
  fail_status_ = status;
  fail_times_ = times;
}

std::vector<HttpTestServer::Request> HttpTestServer::Requests() const {
  const std::lock_guard lock(mutex_);
  return requests_;
}

void HttpTestServer::Run() {
  for (;;) {
    pollfd fds[2] = {{listen_fd_, POLLIN, 0}, {wake_pipe_[0], POLLIN, 0}};
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      return;
    }
    if (fds[1].revents != 0) return;  // asked to stop
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) continue;
    Handle(fd);
    ::close(fd);
  }
}

void HttpTestServer::Handle(int fd) {
  const std::string head = ReadHead(fd);
  if (head.empty()) return;
  Request request;
  const std::size_t line_end = head.find("\r\n");
  const std::string first = head.substr(0, line_end);
  const std::size_t s1 = first.find(' ');
  const std::size_t s2 = first.find(' ', s1 + 1);
  request.method = first.substr(0, s1);
  request.path = first.substr(s1 + 1, s2 - s1 - 1);
  const std::string lower = Lower(head);
  if (const std::size_t at = lower.find("\r\nrange:"); at != std::string::npos) {
    const std::size_t start = head.find_first_not_of(' ', at + 8);
    request.range = head.substr(start, head.find("\r\n", start) - start);
  }

  std::unique_lock lock(mutex_);
  requests_.push_back(request);
  std::string headers;
  std::string body;
  std::size_t send_body = std::string::npos;  // bytes of body to send before closing
  if (fail_times_ > 0) {
    --fail_times_;
    body = "failing on purpose\n";
    headers = StatusLine(fail_status_);
  } else if (const auto redirect = redirects_.find(request.path); redirect != redirects_.end()) {
    headers = StatusLine(302) + "Location: " + redirect->second + "\r\n";
  } else if (const auto found = bodies_.find(request.path); found == bodies_.end()) {
    body = "not found\n";
    headers = StatusLine(404);
  } else {
    const std::string& full = found->second;
    std::size_t first_byte = 0, last_byte = full.empty() ? 0 : full.size() - 1;
    const bool ranged = request.range.rfind("bytes=", 0) == 0 && !ignore_range_;
    if (ranged) {  // only the forms our client sends: "bytes=N-" and "bytes=N-M"
      const std::string spec = request.range.substr(6);
      first_byte = std::strtoull(spec.c_str(), nullptr, 10);
      const std::string last = spec.substr(spec.find('-') + 1);
      if (!last.empty()) last_byte = std::min<std::size_t>(std::strtoull(last.c_str(), nullptr, 10), last_byte);
    }
    if (ranged && first_byte >= full.size()) {
      headers = StatusLine(416) + "Content-Range: bytes */" + std::to_string(full.size()) + "\r\n";
    } else if (ranged) {
      body = full.substr(first_byte, last_byte - first_byte + 1);
      headers = StatusLine(206) + "Content-Range: bytes " + std::to_string(first_byte) + "-" +
                std::to_string(last_byte) + "/" + std::to_string(full.size()) + "\r\n";
    } else {
      body = full;
      headers = StatusLine(200);
    }
    headers += "Accept-Ranges: bytes\r\n";
    if (request.method == "GET" && cut_times_ > 0) {
      --cut_times_;
      send_body = std::min(cut_bytes_, body.size());
    }
  }
  lock.unlock();

  headers += "Content-Length: " + std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n";
  SendAll(fd, headers);
  if (request.method != "HEAD") SendAll(fd, body.substr(0, send_body));
}

}  // namespace dlslam::testing
