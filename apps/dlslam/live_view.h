#pragma once
// `dlslam run --view [PORT]`: the run as it goes, in a browser on this
// machine (http://127.0.0.1:PORT/): the current frame with kept and removed
// keypoints and the removed regions, the trajectory so far (against ground
// truth when there is one), the map points and keyframes in 3-D, timings
// and the tracking state. The page is the --html report's, polling
// data.json and frame.jpg twice a second.
//
// The tracking thread only copies the frame's state under a short lock
// (Publish); drawing, JPEG encoding and reading the map happen on the
// server's own thread when a browser asks, so an open page costs tracking
// nothing but CPU time on a shared core, and no page costs nothing.

#include <nlohmann/json.hpp>

#include <atomic>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <opencv2/core.hpp>

#include "dlslam/system/slam_system.h"

namespace dlslam::app {

struct LiveFrame {
  int frame = 0;  // frames given so far
  int posed = 0;
  std::string state;  // tracking state
  double timestamp = 0.0;
  std::optional<Eigen::Vector3d> position;      // world_from_cam translation
  std::optional<SE3d> world_from_cam;
  std::optional<SE3d> ground_truth;             // at this frame's time
  char source = 't';                            // PoseSourceLetter: t, r, c, n
};

class LiveView {
 public:
  // Listens on 127.0.0.1:`port` (0: any free port). `slam` outlives the
  // view; only its thread-safe calls are used here. Throws dlslam::Error
  // when the port cannot be had.
  LiveView(int port, std::string title, std::string mode, const SlamSystem* slam);
  ~LiveView();
  LiveView(const LiveView&) = delete;
  LiveView& operator=(const LiveView&) = delete;

  int port() const { return port_; }
  // Tracking thread, after each frame: the frame's state and image (the
  // image is shared, not copied: the caller must not write into it later).
  void Publish(const LiveFrame& frame, const cv::Mat& colour, const SlamSystem::FrameView& view, const RunStats* stats);
  // Stops serving and joins the thread. Idempotent.
  void Stop();

 private:
  void Serve();
  std::string Respond(const std::string& path, std::string* type);
  std::string DataJson();
  std::string FrameJpeg();

  std::string title_;
  std::string mode_;
  const SlamSystem* slam_;
  int listen_fd_ = -1;
  int wake_fd_[2] = {-1, -1};
  int port_ = 0;
  std::atomic<bool> stopping_{false};
  std::thread thread_;

  std::mutex mutex_;  // guards everything below
  std::vector<LiveFrame> frames_;
  cv::Mat colour_;
  SlamSystem::FrameView view_;
  nlohmann::ordered_json timings_ = nlohmann::ordered_json::object();
  std::optional<SE3d> gt_from_est_;  // aligned on the first frame with both
};

}  // namespace dlslam::app
