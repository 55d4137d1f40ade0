#include "live_view.h"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <fcntl.h>
#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "dlslam/util/check.h"
#include "frame_view_image.h"
#include "html_report.h"
#include "run_report.h"

namespace dlslam::app {

namespace {

constexpr int kRequestTimeoutMs = 2000;
constexpr std::size_t kMaxRequestBytes = 8192;

void SendAll(int fd, const std::string& bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;  // the browser went away
    sent += static_cast<std::size_t>(n);
  }
}

}  // namespace

LiveView::LiveView(int port, std::string title, std::string mode, const SlamSystem* slam)
    : title_(std::move(title)), mode_(std::move(mode)), slam_(slam) {
  DLSLAM_CHECK(slam_ != nullptr);
  if (port < 0 || port > 65535) throw Error(fmt::format("--view port {} outside 0..65535", port));
  listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0) throw Error(fmt::format("live view: no socket: {}", std::strerror(errno)));
  const int yes = 1;
  ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 || ::listen(listen_fd_, 8) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(listen_fd_);
    throw Error(fmt::format("live view: cannot listen on 127.0.0.1:{}: {}", port, reason));
  }
  socklen_t length = sizeof address;
  ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&address), &length);
  port_ = ntohs(address.sin_port);
  if (::pipe2(wake_fd_, O_CLOEXEC) != 0) {
    ::close(listen_fd_);
    throw Error(fmt::format("live view: no pipe: {}", std::strerror(errno)));
  }
  thread_ = std::thread([this] { Serve(); });
}

LiveView::~LiveView() { Stop(); }

void LiveView::Stop() {
  if (stopping_.exchange(true)) return;
  const char byte = 0;
  [[maybe_unused]] const ssize_t n = ::write(wake_fd_[1], &byte, 1);
  if (thread_.joinable()) thread_.join();
  ::close(listen_fd_);
  ::close(wake_fd_[0]);
  ::close(wake_fd_[1]);
}

void LiveView::Publish(const LiveFrame& frame, const cv::Mat& colour, const SlamSystem::FrameView& view,
                       const RunStats* stats) {
  std::lock_guard lock(mutex_);
  frames_.push_back(frame);
  colour_ = colour;
  view_ = view;
  if (!gt_from_est_ && frame.world_from_cam && frame.ground_truth) {
    gt_from_est_ = *frame.ground_truth * frame.world_from_cam->Inverse();
  }
  if (stats) timings_ = TimingsReport(stats->timing_ms);
}

void LiveView::Serve() {
  while (!stopping_.load()) {
    pollfd fds[2] = {{listen_fd_, POLLIN, 0}, {wake_fd_[0], POLLIN, 0}};
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      return;
    }
    if (fds[1].revents != 0) return;
    if ((fds[0].revents & POLLIN) == 0) continue;
    const int client = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (client < 0) continue;
    std::string request;
    char buffer[2048];
    while (request.find("\r\n\r\n") == std::string::npos && request.size() < kMaxRequestBytes) {
      pollfd in{client, POLLIN, 0};
      if (::poll(&in, 1, kRequestTimeoutMs) <= 0) break;
      const ssize_t n = ::recv(client, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      request.append(buffer, static_cast<std::size_t>(n));
    }
    std::string status = "200 OK", type, body;
    const std::size_t space = request.find(' '), end = request.find(' ', space + 1);
    if (request.rfind("GET ", 0) != 0 || end == std::string::npos) {
      status = "400 Bad Request";
      body = "bad request\n";
      type = "text/plain";
    } else {
      std::string path = request.substr(space + 1, end - space - 1);
      if (const std::size_t q = path.find('?'); q != std::string::npos) path.resize(q);
      try {
        body = Respond(path, &type);
        if (type.empty()) {
          status = "404 Not Found";
          type = "text/plain";
          body = "not found\n";
        }
      } catch (const std::exception& e) {  // a view must never end the run
        status = "500 Internal Server Error";
        type = "text/plain";
        body = std::string(e.what()) + "\n";
      }
    }
    SendAll(client, fmt::format("HTTP/1.1 {}\r\nContent-Type: {}\r\nContent-Length: {}\r\nCache-Control: no-store\r\n"
                                "Connection: close\r\n\r\n",
                                status, type, body.size()) +
                        body);
    ::close(client);
  }
}

std::string LiveView::Respond(const std::string& path, std::string* type) {
  if (path == "/" || path == "/index.html") {
    *type = "text/html; charset=utf-8";
    return HtmlReportPage(nullptr);
  }
  if (path == "/data.json") {
    *type = "application/json";
    return DataJson();
  }
  if (path == "/frame.jpg") {
    *type = "image/jpeg";
    return FrameJpeg();
  }
  type->clear();
  return {};
}

std::string LiveView::DataJson() {
  // The map is read outside our lock, through the system's locked calls.
  const std::vector<Eigen::Vector3d> points = slam_->MapPointPositions();
  const Trajectory keyframes = slam_->KeyFrameTrajectory();
  std::lock_guard lock(mutex_);
  const auto place = [this](const Eigen::Vector3d& p) { return gt_from_est_ ? *gt_from_est_ * p : p; };
  nlohmann::ordered_json d;
  d["title"] = title_;
  const LiveFrame last = frames_.empty() ? LiveFrame{} : frames_.back();
  int counts[4] = {0, 0, 0, 0};
  nlohmann::ordered_json trajectory = nlohmann::ordered_json::array();
  for (const LiveFrame& f : frames_) {
    if (!f.position) continue;
    counts[f.source == 'r' ? 1 : f.source == 'c' ? 2 : f.source == 'n' ? 3 : 0]++;
    nlohmann::ordered_json e;
    e["t"] = f.timestamp;
    e["est"] = PositionMm(place(*f.position));
    if (f.ground_truth && gt_from_est_) {
      e["gt"] = PositionMm(f.ground_truth->translation());
      e["error"] = (place(*f.position) - f.ground_truth->translation()).norm();
    }
    e["source"] = std::string(1, f.source);
    trajectory.push_back(std::move(e));
  }
  d["summary"] = {{"mode", mode_},
                  {"frames", last.frame},
                  {"frames_posed", last.posed},
                  {"state", last.state},
                  {"pose_sources", {{"tracked", counts[0]}, {"relocalized", counts[1]}, {"coasted", counts[2]}, {"new_map", counts[3]}}},
                  {"ate_rmse", nullptr},
                  {"keyframes", keyframes.size()},
                  {"map_points", points.size()}};
  d["trajectory"] = std::move(trajectory);
  nlohmann::ordered_json kf = nlohmann::ordered_json::array();
  for (const StampedPose& k : keyframes) kf.push_back(PositionMm(place(k.translation)));
  d["keyframes"] = std::move(kf);
  d["map_points"] = MapPointsMm(points, place);
  d["timings"] = timings_;
  d["options"] = nullptr;
  return d.dump();
}

std::string LiveView::FrameJpeg() {
  cv::Mat colour;
  SlamSystem::FrameView view;
  {
    std::lock_guard lock(mutex_);
    colour = colour_;
    view = view_;
  }
  const cv::Mat image = DrawFrameView(colour, view);
  std::vector<uchar> jpeg;
  cv::imencode(".jpg", image, jpeg, {cv::IMWRITE_JPEG_QUALITY, 80});
  return std::string(jpeg.begin(), jpeg.end());
}

}  // namespace dlslam::app
