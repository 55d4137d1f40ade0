#pragma once
// Bundle adjustment of keyframe poses and map points (ORB-SLAM's local BA):
// robust reprojection errors (u, v and, with depth, the virtual right u), two
// passes with outlier removal in between. Two interchangeable solvers: Ceres
// (SPARSE_SCHUR, autodiff) and our own sparse Levenberg-Marquardt with a
// Schur complement on the points (lm_bundle_adjuster.cc), which is faster on
// local bundles (docs/slam-core.md). Knows nothing of the map: it takes and
// returns plain values.

#include <Eigen/Core>

#include <atomic>
#include <string>
#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/geometry/se3.h"

namespace dlslam {

struct BundleProblem {
  struct Pose {
    SE3d cam_from_world;
    bool fixed = false;  // seen only for its observations (ORB-SLAM's fixed keyframes)
  };
  struct Observation {
    int pose = 0;   // index into poses
    int point = 0;  // index into points
    Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // undistorted [px]
    double right_u = -1.0;                            // < 0: no depth
    double information = 1.0;                         // 1 / sigma^2 of the octave
  };
  CameraIntrinsics camera;
  std::vector<Pose> poses;
  std::vector<Eigen::Vector3d> points;  // world [m]
  std::vector<Observation> observations;
};

enum class BundleSolver {
  kCeres,  // Ceres SPARSE_SCHUR with autodiff cost functions
  kLm,     // hand-written sparse Levenberg-Marquardt (Schur complement on points)
};
const char* ToString(BundleSolver solver);
// "ceres" or "lm"; throws dlslam::Error naming the text otherwise.
BundleSolver ParseBundleSolver(const std::string& text);

struct BundleAdjusterOptions {
  // Which solver SolveBundle runs (both give the same minimum, tested).
  BundleSolver solver = BundleSolver::kLm;
  // Iterations of the first (robust) pass and of the second pass without outliers.
  int first_pass_iterations = 5;
  int second_pass_iterations = 10;
  // Chi-square gates (95 %) for 2 and 3 dof; also the Huber thresholds squared.
  double chi2_mono = 5.991;
  double chi2_stereo = 7.815;
  // Threads Ceres may use (the LM solver is single-threaded).
  int threads = 1;
  // A pass stops when an accepted step lowers the cost by less than this
  // fraction of it (Ceres' function_tolerance; both solvers).
  double function_tolerance = 1e-6;
  // Set from another thread to stop the solve (the loop closer interrupts a
  // global BA when a new loop arrives). Checked between iterations; the solve
  // then returns early with the best state so far and summary.aborted set.
  // nullptr: never aborted. Not owned; must outlive the call.
  const std::atomic<bool>* abort = nullptr;

  void Check() const;
};

struct BundleSummary {
  int iterations = 0;
  int outliers = 0;           // observations flagged in `outlier`
  double initial_cost = 0.0;  // 0.5 * sum of (robust) squared whitened errors, before and after
  double final_cost = 0.0;
  std::vector<bool> outlier;  // per observation, after the second pass
  bool aborted = false;       // options.abort was seen set; the remaining iterations were skipped
};

// Optimises the non-fixed poses and all points in place with options.solver.
BundleSummary SolveBundle(BundleProblem* problem, const BundleAdjusterOptions& options = {});
// The two solvers themselves (SolveBundle picks one).
BundleSummary SolveBundleCeres(BundleProblem* problem, const BundleAdjusterOptions& options);
BundleSummary SolveBundleLm(BundleProblem* problem, const BundleAdjusterOptions& options);

// Whitened squared error of one observation at the problem's current values
// (infinite when the point is not in front of the camera).
double ObservationChi2(const BundleProblem& problem, const BundleProblem::Observation& observation);

}  // namespace dlslam
