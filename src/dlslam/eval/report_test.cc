#include "dlslam/eval/report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace dlslam::eval {
namespace {

using ::testing::HasSubstr;

ErrorStats Stats(double base) { return {base, base + 1, base + 2, base + 3, base + 4, base + 5}; }

TEST(ReportTest, AteJsonHasTheReferenceKeysInOrder) {
  AteResult r;
  r.pairs = 3;
  r.error = Stats(0.5);
  EXPECT_EQ(DumpJsonLine(ToJson(r)),
            R"({"pairs": 3, "rmse": 0.5, "mean": 1.5, "median": 2.5, "std": 3.5, "min": 4.5, "max": 5.5})");
}

TEST(ReportTest, RpeJsonNestsTranslationAndRotation) {
  RpeResult r;
  r.pairs = 7;
  r.translation = Stats(0.25);
  r.rotation_deg = Stats(10);
  EXPECT_EQ(DumpJsonLine(ToJson(r)),
            R"({"pairs": 7, "translation": {"rmse": 0.25, "mean": 1.25, "median": 2.25, "std": 3.25, )"
            R"("min": 4.25, "max": 5.25}, "rotation_deg": {"rmse": 10.0, "mean": 11.0, "median": 12.0, )"
            R"("std": 13.0, "min": 14.0, "max": 15.0}})");
}

TEST(ReportTest, DoublesKeepFullPrecision) {
  AteResult r;
  r.error.rmse = 0.1 + 0.2;  // 0.30000000000000004
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(DumpJsonLine(ToJson(r)));
  EXPECT_EQ(j["rmse"].get<double>(), 0.1 + 0.2);
}

TEST(ReportTest, TablesNameEveryStatistic) {
  AteResult a;
  a.pairs = 12;
  a.error = Stats(0.01);
  const std::string ate = FormatAteTable(a, {});
  for (const char* word : {"12 pose pairs", "rmse", "mean", "median", "std", "min", "max", "0.010000"}) {
    EXPECT_THAT(ate, HasSubstr(word));
  }
  RpeResult r;
  r.pairs = 5;
  r.translation = Stats(0.02);
  r.rotation_deg = Stats(0.7);
  const std::string rpe = FormatRpeTable(r, {.delta = 2.0, .delta_unit = DeltaUnit::kFrames});
  EXPECT_THAT(rpe, HasSubstr("delta 2 f"));
  EXPECT_THAT(rpe, HasSubstr("rotation [deg]"));
  EXPECT_THAT(rpe, HasSubstr("0.700000"));
}

}  // namespace
}  // namespace dlslam::eval
