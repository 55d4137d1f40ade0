#include "dlslam/eval/report.h"

#include <fmt/format.h>

namespace dlslam::eval {

namespace {

void AddStats(const ErrorStats& stats, nlohmann::ordered_json& j) {
  j["rmse"] = stats.rmse;
  j["mean"] = stats.mean;
  j["median"] = stats.median;
  j["std"] = stats.std;
  j["min"] = stats.min;
  j["max"] = stats.max;
}

}  // namespace

nlohmann::ordered_json ToJson(const ErrorStats& stats) {
  nlohmann::ordered_json j;
  AddStats(stats, j);
  return j;
}

nlohmann::ordered_json ToJson(const AteResult& result) {
  nlohmann::ordered_json j;
  j["pairs"] = result.pairs;
  AddStats(result.error, j);
  return j;
}

nlohmann::ordered_json ToJson(const RpeResult& result) {
  nlohmann::ordered_json j;
  j["pairs"] = result.pairs;
  j["translation"] = ToJson(result.translation);
  j["rotation_deg"] = ToJson(result.rotation_deg);
  return j;
}

std::string DumpJsonLine(const nlohmann::ordered_json& json) {
  if (json.is_object()) {
    std::string out = "{";
    for (auto it = json.begin(); it != json.end(); ++it) {
      if (it != json.begin()) out += ", ";
      out += nlohmann::ordered_json(it.key()).dump() + ": " + DumpJsonLine(it.value());
    }
    return out + "}";
  }
  if (json.is_array()) {
    std::string out = "[";
    for (std::size_t k = 0; k < json.size(); ++k) {
      if (k > 0) out += ", ";
      out += DumpJsonLine(json[k]);
    }
    return out + "]";
  }
  return json.dump();
}

namespace {

std::string StatsRow(const char* name, double a) { return fmt::format("  {:<8}{:>12.6f}\n", name, a); }

std::string StatsRow(const char* name, double a, double b) {
  return fmt::format("  {:<8}{:>16.6f}{:>16.6f}\n", name, a, b);
}

}  // namespace

std::string FormatAteTable(const AteResult& result, const AteOptions& options) {
  const ErrorStats& e = result.error;
  std::string out = fmt::format(
      "ATE: {} pose pairs (max-diff {} s, offset {} s, scale {}), after rigid alignment\n",
      result.pairs, options.max_diff, options.offset, options.scale);
  out += "  (errors in m)\n";
  out += StatsRow("rmse", e.rmse) + StatsRow("mean", e.mean) + StatsRow("median", e.median) +
         StatsRow("std", e.std) + StatsRow("min", e.min) + StatsRow("max", e.max);
  return out;
}

std::string FormatRpeTable(const RpeResult& result, const RpeOptions& options) {
  const ErrorStats& t = result.translation;
  const ErrorStats& r = result.rotation_deg;
  std::string out = fmt::format("RPE: {} pose pairs, delta {} {} (offset {} s, scale {})\n",
                                result.pairs, options.delta, ToString(options.delta_unit),
                                options.offset, options.scale);
  out += fmt::format("  {:<8}{:>16}{:>16}\n", "", "translation [m]", "rotation [deg]");
  out += StatsRow("rmse", t.rmse, r.rmse) + StatsRow("mean", t.mean, r.mean) +
         StatsRow("median", t.median, r.median) + StatsRow("std", t.std, r.std) +
         StatsRow("min", t.min, r.min) + StatsRow("max", t.max, r.max);
  return out;
}

}  // namespace dlslam::eval
