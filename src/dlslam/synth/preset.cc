#include "dlslam/synth/preset.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <utility>

#include "dlslam/util/check.h"

namespace dlslam::synth {

namespace {
constexpr std::array<std::pair<Preset, const char*>, 8> kNames = {{
    {Preset::kStatic, "static"},
    {Preset::kWalkingXyz, "walking_xyz"},
    {Preset::kWalkingRpy, "walking_rpy"},
    {Preset::kWalkingHalfsphere, "walking_halfsphere"},
    {Preset::kWalkingStatic, "walking_static"},
    {Preset::kSittingStatic, "sitting_static"},
    {Preset::kKidnap, "kidnap"},
    {Preset::kLoop, "loop"},
}};
}  // namespace

Preset ParsePreset(std::string_view name) {
  for (const auto& [preset, text] : kNames) {
    if (name == text) return preset;
  }
  throw Error(fmt::format("unknown synth preset '{}' (known: {})", name, fmt::join(PresetNames(), ", ")));
}

std::string PresetName(Preset preset) {
  for (const auto& [p, text] : kNames) {
    if (p == preset) return text;
  }
  return "?";
}

std::vector<std::string> PresetNames() {
  std::vector<std::string> names;
  for (const auto& entry : kNames) names.emplace_back(entry.second);
  return names;
}

}  // namespace dlslam::synth
