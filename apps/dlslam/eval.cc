// dlslam eval ate|rpe: trajectory accuracy exactly as the TUM RGB-D benchmark
// tools (evaluate_ate.py, evaluate_rpe.py --fixed_delta) compute it.

#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <string>

#include "cli_checks.h"
#include "commands.h"
#include "dlslam/eval/ate.h"
#include "dlslam/eval/ground_truth_convention.h"
#include "dlslam/eval/plot.h"
#include "dlslam/eval/report.h"
#include "dlslam/eval/rpe.h"
#include "dlslam/io/file_util.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/util/check.h"

namespace dlslam::app {

namespace {

struct EvalArgs {
  std::string gt;
  std::string est;
  double offset = 0.0;
  double scale = 1.0;
  bool json = false;
  std::string plot;
  std::string gt_convention = "published";
};

void AddCommonOptions(CLI::App* cmd, EvalArgs& args) {
  cmd->add_option("--gt", args.gt, "Ground-truth trajectory (TUM format)")->required();
  cmd->add_option("--est", args.est, "Estimated trajectory (TUM format)")->required();
  cmd->add_option("--offset", args.offset, "Time offset added to the estimate's timestamps [s]")
      ->capture_default_str()->check(RealNumber(-1e9, 1e9));
  cmd->add_option("--scale", args.scale, "Scale applied to the estimate's translations")
      ->capture_default_str()->check(RealNumber(1e-9, 1e9));
  cmd->add_option("--gt-convention", args.gt_convention,
                  "Whose poses the ground truth holds: published (as the file says) | bonn-camera (Bonn RGB-D "
                  "Dynamic marker poses turned into the camera's with the dataset's transform)")
      ->capture_default_str()
      ->check(CLI::IsMember({"published", "bonn-camera"}));
  cmd->add_flag("--json", args.json, "Print the result as one line of JSON");
  cmd->add_option("--plot", args.plot, "Write a plot: out.svg or out.png");
}

Trajectory Read(const std::string& path) {
  io::TrajectoryReadOptions options;
  options.min_poses = 2;
  return io::ReadTumTrajectory(path, options);
}

// Library errors know no file names; say which files they are about.
template <typename F>
auto NamingFiles(const EvalArgs& args, F&& compute) {
  try {
    return compute();
  } catch (const InputError&) {
    throw;
  } catch (const Error& e) {
    throw Error(fmt::format("evaluating {} against {}: {}", args.est, args.gt, e.what()));
  }
}

template <typename Result>
void WritePlot(const std::string& path, const Result& result, std::string (*svg)(const Result&),
               cv::Mat (*image)(const Result&)) {
  if (eval::PlotFormatFromPath(path) == eval::PlotFormat::kSvg) {
    const std::string text = svg(result);
    io::WriteFileAtomically(path, [&](std::ostream& out) { out << text; });
  } else {
    const std::vector<unsigned char> png = eval::EncodePng(image(result));
    io::WriteFileAtomically(path, [&](std::ostream& out) {
      out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
    });
  }
}

Trajectory ReadGroundTruth(const EvalArgs& args) {
  return eval::ToCameraPoses(Read(args.gt), eval::ParseGroundTruthConvention(args.gt_convention));
}

void RunAte(const EvalArgs& args, const eval::AteOptions& options) {
  options.Check();
  if (!args.plot.empty()) eval::PlotFormatFromPath(args.plot);  // fail before the work
  const Trajectory gt = ReadGroundTruth(args);
  const Trajectory est = Read(args.est);
  const eval::AteResult result = NamingFiles(args, [&] { return eval::ComputeAte(gt, est, options); });
  if (args.json) {
    std::cout << eval::DumpJsonLine(eval::ToJson(result)) << '\n';
  } else {
    std::cout << eval::FormatAteTable(result, options);
  }
  if (!args.plot.empty()) {
    WritePlot<eval::AteResult>(args.plot, result, eval::AtePlotSvg, eval::AtePlotImage);
    if (!args.json) std::cout << "plot: " << args.plot << '\n';
  }
}

void RunRpe(const EvalArgs& args, const eval::RpeOptions& options) {
  options.Check();
  if (!args.plot.empty()) eval::PlotFormatFromPath(args.plot);
  const Trajectory gt = ReadGroundTruth(args);
  const Trajectory est = Read(args.est);
  const eval::RpeResult result = NamingFiles(args, [&] { return eval::ComputeRpe(gt, est, options); });
  if (args.json) {
    std::cout << eval::DumpJsonLine(eval::ToJson(result)) << '\n';
  } else {
    std::cout << eval::FormatRpeTable(result, options);
  }
  if (!args.plot.empty()) {
    WritePlot<eval::RpeResult>(args.plot, result, eval::RpePlotSvg, eval::RpePlotImage);
    if (!args.json) std::cout << "plot: " << args.plot << '\n';
  }
}

}  // namespace

void AddEvalCommand(CLI::App& app) {
  CLI::App* eval_cmd = app.add_subcommand("eval", "Trajectory accuracy as the TUM RGB-D benchmark tools");
  eval_cmd->require_subcommand(1);

  auto ate_args = std::make_shared<EvalArgs>();
  auto ate_options = std::make_shared<eval::AteOptions>();
  CLI::App* ate = eval_cmd->add_subcommand(
      "ate", "Absolute trajectory error after rigid alignment (evaluate_ate.py)");
  AddCommonOptions(ate, *ate_args);
  ate->add_option("--max-diff", ate_options->max_diff,
                  "Largest time difference of matched poses [s]")
      ->capture_default_str()->check(RealNumber(1e-9, 1000));
  ate->callback([ate_args, ate_options] {
    ate_options->offset = ate_args->offset;
    ate_options->scale = ate_args->scale;
    RunAte(*ate_args, *ate_options);
  });

  auto rpe_args = std::make_shared<EvalArgs>();
  auto rpe_options = std::make_shared<eval::RpeOptions>();
  auto rpe_unit = std::make_shared<std::string>("s");
  CLI::App* rpe = eval_cmd->add_subcommand(
      "rpe", "Relative pose error over a fixed delta (evaluate_rpe.py --fixed_delta, all pairs)");
  AddCommonOptions(rpe, *rpe_args);
  rpe->add_option("--delta", rpe_options->delta, "Distance between the poses of a pair, in --delta-unit")
      ->capture_default_str()->check(RealNumber(1e-9, 1e9));
  rpe->add_option("--delta-unit", *rpe_unit, "s | m | rad | deg | f (seconds, metres, radians, degrees, frames)")
      ->check(CLI::IsMember({"s", "m", "rad", "deg", "f"}))
      ->capture_default_str();
  rpe->callback([rpe_args, rpe_options, rpe_unit] {
    rpe_options->delta_unit = eval::ParseDeltaUnit(*rpe_unit);
    rpe_options->offset = rpe_args->offset;
    rpe_options->scale = rpe_args->scale;
    RunRpe(*rpe_args, *rpe_options);
  });
}

}  // namespace dlslam::app
