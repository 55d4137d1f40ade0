#pragma once
// Results as JSON (the keys and order of the reference scripts in
// scripts/tum_reference) and as a human-readable table.

#include <nlohmann/json.hpp>

#include <string>

#include "dlslam/eval/ate.h"
#include "dlslam/eval/rpe.h"

namespace dlslam::eval {

// {"rmse", "mean", "median", "std", "min", "max"}
nlohmann::ordered_json ToJson(const ErrorStats& stats);
// {"pairs": N, "rmse": .., "mean": .., "median": .., "std": .., "min": .., "max": ..}
nlohmann::ordered_json ToJson(const AteResult& result);
// {"pairs": N, "translation": {six keys}, "rotation_deg": {six keys}}
nlohmann::ordered_json ToJson(const RpeResult& result);

// One line laid out as Python's json.dumps: {"a": 1, "b": [2, 3]}. Doubles
// in the shortest form that reads back to the same value.
std::string DumpJsonLine(const nlohmann::ordered_json& json);

std::string FormatAteTable(const AteResult& result, const AteOptions& options);
std::string FormatRpeTable(const RpeResult& result, const RpeOptions& options);

}  // namespace dlslam::eval
