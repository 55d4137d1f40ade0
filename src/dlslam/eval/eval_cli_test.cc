// `dlslam eval` run as a user runs it: JSON equal to the reference fixtures,
// plots written, bad input refused with the file named and a non-zero exit.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "dlslam/eval/ground_truth_convention.h"
#include "tests/support/cli_run.h"
#include "tests/support/test_data.h"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using dlslam::testing::CliRun;
using dlslam::testing::Quoted;

// Runs the CLI through the shell; `redirect` is appended (e.g. "2>&1").
CliRun Cli(const std::string& args, const std::string& redirect = "2>/dev/null") {
  return dlslam::testing::RunShell(Quoted(DLSLAM_CLI_PATH) + " " + args + " " + redirect);
}

class EvalCliTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = dlslam::testing::MakeTempDir("eval_cli"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path Case(const std::string& name) { return dlslam::testing::FixturePath("eval/" + name); }
  std::string Files(const std::string& name) {
    return "--gt " + Quoted(Case(name) / "gt.txt") + " --est " + Quoted(Case(name) / "est.txt");
  }
  static nlohmann::json Expected(const fs::path& file) {
    nlohmann::json doc;
    std::ifstream(file) >> doc;
    return doc.at("result");
  }
  static void ExpectStatsNear(const nlohmann::json& cpp, const nlohmann::json& ref) {
    for (const char* key : {"rmse", "mean", "median", "std", "min", "max"}) {
      const double r = ref.at(key);
      EXPECT_NEAR(cpp.at(key).get<double>(), r, 1e-6 * std::max(1.0, std::abs(r))) << key;
    }
  }
  fs::path dir_;
};

TEST_F(EvalCliTest, AteJsonMatchesTheReference) {
  const CliRun run = Cli("eval ate " + Files("scale") + " --scale 2.5 --json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(run.output.starts_with("{\"pairs\": ")) << run.output;
  const nlohmann::json cpp = nlohmann::json::parse(run.output);
  const nlohmann::json ref = Expected(Case("scale") / "expected_ate.json");
  EXPECT_EQ(cpp.at("pairs"), ref.at("pairs"));
  ExpectStatsNear(cpp, ref);
  EXPECT_EQ(cpp.size(), 7u);  // no extra keys
}

TEST_F(EvalCliTest, RpeJsonMatchesTheReference) {
  const CliRun run = Cli("eval rpe " + Files("spin") + " --delta 20 --delta-unit deg --json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json cpp = nlohmann::json::parse(run.output);
  const nlohmann::json ref = Expected(Case("spin") / "expected_rpe_deg.json");
  EXPECT_EQ(cpp.at("pairs"), ref.at("pairs"));
  ExpectStatsNear(cpp.at("translation"), ref.at("translation"));
  ExpectStatsNear(cpp.at("rotation_deg"), ref.at("rotation_deg"));
}

TEST_F(EvalCliTest, BonnMarkerPosesAreTurnedIntoTheCamerasOnRequest) {
  // A turning, moving marker (a handheld sensor) and the camera poses the
  // dataset's transform gives: a perfect estimate against the camera, with
  // RPE errors against the marker (its turns are about another centre).
  std::ofstream gt(dir_ / "gt.txt"), est(dir_ / "est.txt");
  for (int i = 0; i < 60; ++i) {
    const double t = i / 30.0;
    const dlslam::SE3d marker(
        Eigen::Quaterniond(Eigen::AngleAxisd(0.6 * std::sin(t), Eigen::Vector3d(0.2, 1, 0.1).normalized())),
        Eigen::Vector3d(0.3 * t, -1.5, 1.5 + 0.1 * std::sin(2 * t)));
    const dlslam::SE3d camera = dlslam::eval::BonnCameraFromMarker(marker);
    const auto line = [t](const dlslam::SE3d& p) {
      const Eigen::Quaterniond& q = p.unit_quaternion();
      return fmt::format("{:.6f} {:.9f} {:.9f} {:.9f} {:.9f} {:.9f} {:.9f} {:.9f}\n", 1000 + t, p.translation().x(),
                         p.translation().y(), p.translation().z(), q.x(), q.y(), q.z(), q.w());
    };
    gt << line(marker);
    est << line(camera);
  }
  gt.close();
  est.close();
  const std::string files = "--gt " + Quoted(dir_ / "gt.txt") + " --est " + Quoted(dir_ / "est.txt");
  const auto rpe_deg = [](const CliRun& run) {
    return nlohmann::json::parse(run.output).at("rotation_deg").at("rmse").get<double>();
  };
  const CliRun camera = Cli("eval rpe " + files + " --delta 0.5 --gt-convention bonn-camera --json");
  ASSERT_EQ(camera.exit_code, 0) << camera.output;
  EXPECT_LT(rpe_deg(camera), 1e-4);
  const CliRun published = Cli("eval rpe " + files + " --delta 0.5 --json");
  ASSERT_EQ(published.exit_code, 0) << published.output;
  EXPECT_GT(rpe_deg(published), 1.0);
  const CliRun ate = Cli("eval ate " + files + " --gt-convention bonn-camera --json");
  ASSERT_EQ(ate.exit_code, 0) << ate.output;
  EXPECT_LT(nlohmann::json::parse(ate.output).at("rmse").get<double>(), 1e-6);
  const CliRun unknown = Cli("eval ate " + files + " --gt-convention camera", "2>&1");
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_THAT(unknown.output, HasSubstr("published,bonn-camera"));
}

TEST_F(EvalCliTest, OffsetReachesTheComputation) {
  const CliRun run = Cli("eval rpe " + Files("offset") + " --offset 0.35 --json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json ref = Expected(Case("offset") / "expected_rpe_s.json");
  ExpectStatsNear(nlohmann::json::parse(run.output).at("translation"), ref.at("translation"));
}

TEST_F(EvalCliTest, TableByDefaultAndPlotsByExtension) {
  const fs::path svg = dir_ / "ate.svg";
  const fs::path png = dir_ / "rpe.png";
  const CliRun ate = Cli("eval ate " + Files("handheld") + " --plot " + Quoted(svg));
  ASSERT_EQ(ate.exit_code, 0) << ate.output;
  EXPECT_THAT(ate.output, HasSubstr("rmse"));
  EXPECT_THAT(ate.output, HasSubstr("652 pose pairs"));
  std::ifstream svg_in(svg);
  std::string head(5, '\0');
  svg_in.read(head.data(), 5);
  EXPECT_EQ(head, "<?xml");
  const CliRun rpe = Cli("eval rpe " + Files("handheld") + " --plot " + Quoted(png));
  ASSERT_EQ(rpe.exit_code, 0) << rpe.output;
  EXPECT_THAT(rpe.output, HasSubstr("rotation [deg]"));
  EXPECT_GT(fs::file_size(png), 1000u);
}

TEST_F(EvalCliTest, BadInputExitsNonZeroNamingTheProblem) {
  const fs::path single = dir_ / "single.txt";
  std::ofstream(single) << "1.0 0 0 0 0 0 0 1\n";
  CliRun run = Cli("eval ate --gt " + Quoted(single) + " --est " + Quoted(Case("spin") / "est.txt"), "2>&1");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.output, HasSubstr("single.txt"));
  EXPECT_THAT(run.output, HasSubstr("need at least 2"));

  run = Cli("eval ate --gt missing.txt --est " + Quoted(Case("spin") / "est.txt"), "2>&1");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.output, HasSubstr("missing.txt"));

  // The spin case starts at t = 1000 s, the handheld one at 1.3e9 s.
  run = Cli("eval ate --gt " + Quoted(Case("spin") / "gt.txt") + " --est " +
                Quoted(Case("handheld") / "est.txt"),
            "2>&1");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.output, HasSubstr("no overlap in time between GT and EST within max-diff 0.02 s"));
  EXPECT_THAT(run.output, HasSubstr("handheld"));

  run = Cli("eval ate " + Files("spin") + " --plot " + Quoted(dir_ / "plot.jpg"), "2>&1");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.output, HasSubstr("expected .svg or .png"));
  EXPECT_FALSE(fs::exists(dir_ / "plot.jpg"));

  run = Cli("eval rpe " + Files("spin") + " --delta-unit mm", "2>&1");
  EXPECT_NE(run.exit_code, 0);
  run = Cli("eval rpe " + Files("spin") + " --delta -1", "2>&1");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.output, HasSubstr("--delta: expected a number in [1e-09, 1000000000], got '-1'"));
  run = Cli("eval rpe " + Files("spin") + " --delta 0.5 --delta-unit f", "2>&1");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, HasSubstr("must be at least 1"));
  run = Cli("eval ate " + Files("spin") + " --max-diff 0", "2>&1");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.output, HasSubstr("--max-diff: expected a number in [1e-09, 1000], got '0'"));
}

}  // namespace
