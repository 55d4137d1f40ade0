#include "dlslam/system/dynamic_options.h"

#include "dlslam/util/check.h"

namespace dlslam {

const char* ToString(DynamicMode mode) {
  switch (mode) {
    case DynamicMode::kOrb: return "orb";
    case DynamicMode::kSemantic: return "semantic";
    case DynamicMode::kGeometry: return "geometry";
    case DynamicMode::kFull: return "full";
  }
  return "?";
}

DynamicMode ParseDynamicMode(const std::string& name) {
  for (DynamicMode mode : {DynamicMode::kOrb, DynamicMode::kSemantic, DynamicMode::kGeometry, DynamicMode::kFull}) {
    if (name == ToString(mode)) return mode;
  }
  throw Error(fmt::format("unknown dynamic mode '{}' (choose orb, semantic, geometry or full)", name));
}

bool UsesSemanticPrior(DynamicMode mode) { return mode == DynamicMode::kSemantic || mode == DynamicMode::kFull; }
bool UsesGeometry(DynamicMode mode) { return mode == DynamicMode::kGeometry || mode == DynamicMode::kFull; }

void DynamicOptions::Check() const {
  DLSLAM_CHECK(mode == DynamicMode::kOrb || mode == DynamicMode::kSemantic || mode == DynamicMode::kGeometry ||
                   mode == DynamicMode::kFull,
               "unknown dynamic mode {}", static_cast<int>(mode));
  geometry.Check();
  fusion.Check();
  completion.Check();
  DLSLAM_CHECK(inverted_check_min_share > 0 && inverted_check_min_share <= 1,
               "DynamicOptions::inverted_check_min_share {} outside (0, 1]", inverted_check_min_share);
  DLSLAM_CHECK(max_geometry_share_of_prior_static > 0 && max_geometry_share_of_prior_static <= 1,
               "DynamicOptions::max_geometry_share_of_prior_static {} outside (0, 1]",
               max_geometry_share_of_prior_static);
}

dynamic::GeometryOptions DynamicOptions::GeometryInMode() const {
  dynamic::GeometryOptions g = geometry;
  if (mode == DynamicMode::kGeometry && !geometry_mode_parallax_check) g.multiview.parallax_occlusion_check = false;
  return g;
}

}  // namespace dlslam
