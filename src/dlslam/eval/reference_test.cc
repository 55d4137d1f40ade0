// Every fixture in tests/fixtures/eval against the independent Python
// reference (scripts/tum_reference, run by scripts/make_eval_fixtures.py).
// Numbers agree when |cpp - ref| <= 1e-6 * max(1, |ref|): absolute 1e-6 for
// values up to 1 (metres, degrees), relative 1e-6 above. Counts and
// associations must be identical.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <vector>

#include "dlslam/eval/associate.h"
#include "dlslam/eval/ate.h"
#include "dlslam/eval/report.h"
#include "dlslam/eval/rpe.h"
#include "dlslam/io/trajectory_io.h"
#include "tests/support/test_data.h"

namespace dlslam::eval {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kTolerance = 1e-6;

struct Agreement {
  double max_abs = 0.0;
  std::string max_abs_what;
  double max_rel = 0.0;  // over |ref| >= 1e-6: a relative difference of ~0 means nothing
  std::string max_rel_what;
  int numbers = 0;
};

Agreement& Total() {
  static Agreement total;
  return total;
}

void ExpectClose(double cpp, double ref, const std::string& what) {
  const double abs_diff = std::abs(cpp - ref);
  Agreement& t = Total();
  if (abs_diff > t.max_abs) {
    t.max_abs = abs_diff;
    t.max_abs_what = what;
  }
  if (std::abs(ref) >= 1e-6 && abs_diff / std::abs(ref) > t.max_rel) {
    t.max_rel = abs_diff / std::abs(ref);
    t.max_rel_what = what;
  }
  ++t.numbers;
  EXPECT_LE(abs_diff, kTolerance * std::max(1.0, std::abs(ref)))
      << what << ": C++ " << cpp << " vs. reference " << ref;
}

void ExpectStats(const json& cpp, const json& ref, const std::string& what) {
  for (const char* key : {"rmse", "mean", "median", "std", "min", "max"}) {
    ExpectClose(cpp.at(key).get<double>(), ref.at(key).get<double>(), what + " " + key);
  }
}

std::vector<fs::path> ExpectedFiles() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(testing::FixturePath("eval"))) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("expected_") && name.ends_with(".json")) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// One reference run; ASSERTs end only this file's checks.
void CheckRun(const fs::path& file, std::map<std::string, int>& kinds) {
  SCOPED_TRACE(file.string());
  const std::string run = file.parent_path().filename().string() + "/" + file.filename().string();
  json doc;
  std::ifstream(file) >> doc;
  const json& params = doc.at("params");
  const json& ref = doc.at("result");
  const std::string kind = doc.at("kind");
  ++kinds[kind == "rpe" ? "rpe_" + params.at("delta_unit").get<std::string>() : kind];
  const Trajectory gt = io::ReadTumTrajectory(file.parent_path() / "gt.txt");
  const Trajectory est = io::ReadTumTrajectory(file.parent_path() / "est.txt");
  if (kind == "associate") {
    const std::vector<TimestampMatch> m = Associate(gt, est, {params.at("max_diff"), params.at("offset")});
    ASSERT_EQ(m.size(), ref.at("pairs").get<std::size_t>());
    for (std::size_t k = 0; k < m.size(); ++k) {
      ASSERT_EQ(m[k].gt_index, ref["matches"][k][0].get<std::size_t>()) << k;
      ASSERT_EQ(m[k].est_index, ref["matches"][k][1].get<std::size_t>()) << k;
    }
  } else if (kind == "ate") {
    const AteOptions options{params.at("max_diff"), params.at("offset"), params.at("scale")};
    const AteResult r = ComputeAte(gt, est, options);
    ASSERT_EQ(r.pairs, ref.at("pairs").get<std::size_t>());
    ExpectStats(ToJson(r), ref, run);
    for (int i = 0; i < 3; ++i) {
      ExpectClose(r.gt_from_est.translation[i], ref["translation"][i], run + " translation");
      for (int j = 0; j < 3; ++j) ExpectClose(r.gt_from_est.rotation(i, j), ref["rotation"][i][j], run + " rotation");
    }
  } else {
    ASSERT_EQ(kind, "rpe");
    const RpeOptions options{params.at("delta"), ParseDeltaUnit(params.at("delta_unit").get<std::string>()),
                             params.at("offset"), params.at("scale")};
    const RpeResult r = ComputeRpe(gt, est, options);
    ASSERT_EQ(r.pairs, ref.at("pairs").get<std::size_t>());
    const json cpp = ToJson(r);
    ExpectStats(cpp.at("translation"), ref.at("translation"), run + " translation");
    ExpectStats(cpp.at("rotation_deg"), ref.at("rotation_deg"), run + " rotation_deg");
  }
}

TEST(ReferenceTest, EveryFixtureMatchesTheTumReference) {
  const std::vector<fs::path> files = ExpectedFiles();
  ASSERT_GE(files.size(), 20u) << "fixtures missing: run scripts/make_eval_fixtures.py";
  std::map<std::string, int> kinds;
  for (const fs::path& file : files) CheckRun(file, kinds);
  // Every kind of run is covered.
  for (const char* kind : {"associate", "ate", "rpe_s", "rpe_m", "rpe_rad", "rpe_deg", "rpe_f"}) {
    EXPECT_GE(kinds[kind], 1) << kind;
  }
  std::cout << "[ agreement ] " << files.size() << " reference runs, " << Total().numbers
            << " numbers: max |C++ - ref| = " << Total().max_abs << " (" << Total().max_abs_what
            << "), max relative (|ref| >= 1e-6) = " << Total().max_rel << " (" << Total().max_rel_what << ")\n";
}

}  // namespace
}  // namespace dlslam::eval
