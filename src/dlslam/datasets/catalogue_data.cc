// The catalogue's data: which sequences exist and where their archives are.
// Sources: the TUM RGB-D download page (cvg.cit.tum.de/data/datasets/rgbd-dataset/download)
// and the Bonn RGB-D Dynamic page (www.ipb.uni-bonn.de/data/rgbd-dynamic-dataset).
// Neither publishes archive sizes or checksums next to the links, so those
// fields stay empty until someone measures them on the real files; the fetch
// then checks the server's Content-Length / Content-Range total instead.
// To record a measured value: {3, "walking_xyz", "dynamic", <bytes>, "<sha256>"}.

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "dlslam/datasets/catalogue.h"

namespace dlslam::datasets {
namespace {

struct TumEntry {
  int freiburg;               // 1, 2 or 3: the sensor / server folder
  std::string_view name;      // after "rgbd_dataset_freiburgN_"
  std::string_view category;  // as grouped on the download page
  std::uint64_t size_bytes = 0;  // 0 = not known
  std::string_view sha256 = {};  // empty = not known
  std::string_view md5 = {};     // empty = not known
};

struct BonnEntry {
  std::string_view name;  // after "rgbd_bonn_"
  std::uint64_t size_bytes = 0;
  std::string_view sha256 = {};
  std::string_view md5 = {};
};

constexpr TumEntry kTum[] = {
    {1, "xyz", "testing"}, {1, "rpy", "testing"}, {2, "xyz", "testing"}, {2, "rpy", "testing"},
    {1, "360", "handheld"}, {1, "floor", "handheld"}, {1, "desk", "handheld"},
    {1, "desk2", "handheld"}, {1, "room", "handheld"}, {2, "360_hemisphere", "handheld"},
    {2, "360_kidnap", "handheld"}, {2, "desk", "handheld"}, {2, "large_no_loop", "handheld"},
    {2, "large_with_loop", "handheld"}, {3, "long_office_household", "handheld"},
    {2, "pioneer_360", "robot"}, {2, "pioneer_slam", "robot"}, {2, "pioneer_slam2", "robot"},
    {2, "pioneer_slam3", "robot"},
    {3, "nostructure_notexture_far", "structure_texture"},
    {3, "nostructure_notexture_near_withloop", "structure_texture"},
    {3, "nostructure_texture_far", "structure_texture"},
    {3, "nostructure_texture_near_withloop", "structure_texture"},
    {3, "structure_notexture_far", "structure_texture"},
    {3, "structure_notexture_near", "structure_texture"},
    {3, "structure_texture_far", "structure_texture"},
    {3, "structure_texture_near", "structure_texture"},
    {2, "desk_with_person", "dynamic"}, {3, "sitting_static", "dynamic"},
    {3, "sitting_xyz", "dynamic"}, {3, "sitting_halfsphere", "dynamic"},
    {3, "sitting_rpy", "dynamic"}, {3, "walking_static", "dynamic"},
    {3, "walking_xyz", "dynamic"}, {3, "walking_halfsphere", "dynamic"},
    {3, "walking_rpy", "dynamic"},
    {1, "plant", "reconstruction"}, {1, "teddy", "reconstruction"}, {2, "coke", "reconstruction"},
    {2, "dishes", "reconstruction"}, {2, "flowerbouquet", "reconstruction"},
    {2, "flowerbouquet_brownbackground", "reconstruction"},
    {2, "metallic_sphere", "reconstruction"}, {2, "metallic_sphere2", "reconstruction"},
    {3, "cabinet", "reconstruction"}, {3, "large_cabinet", "reconstruction"},
    {3, "teddy", "reconstruction"},
    // Validation sequences: no public ground truth (online evaluation only).
    {1, "xyz_validation", "validation"}, {1, "rpy_validation", "validation"},
    {1, "desk_validation", "validation"}, {1, "desk2_validation", "validation"},
    {1, "360_validation", "validation"}, {1, "room_validation", "validation"},
    {1, "plant_validation", "validation"}, {2, "xyz_validation", "validation"},
    {2, "rpy_validation", "validation"}, {2, "360_hemisphere_validation", "validation"},
    {2, "360_kidnap_validation", "validation"}, {2, "desk_validation", "validation"},
    {2, "desk_with_person_validation", "validation"},
    {2, "pioneer_360_validation", "validation"}, {3, "cabinet_validation", "validation"},
    {3, "large_cabinet_validation", "validation"},
    {3, "long_office_household_validation", "validation"},
    {3, "nostructure_notexture_far_validation", "validation"},
    {3, "nostructure_notexture_near_withloop_validation", "validation"},
    {3, "nostructure_texture_far_validation", "validation"},
    {3, "nostructure_texture_near_withloop_validation", "validation"},
    {3, "structure_notexture_far_validation", "validation"},
    {3, "structure_notexture_near_validation", "validation"},
    {3, "structure_texture_far_validation", "validation"},
    {3, "structure_texture_near_validation", "validation"},
    {3, "sitting_static_validation", "validation"}, {3, "sitting_xyz_validation", "validation"},
    {3, "sitting_halfsphere_validation", "validation"},
    {3, "sitting_rpy_validation", "validation"}, {3, "walking_static_validation", "validation"},
    {3, "walking_xyz_validation", "validation"},
    {3, "walking_halfsphere_validation", "validation"},
    {3, "walking_rpy_validation", "validation"},
    {1, "rgb_calibration", "calibration"}, {1, "ir_calibration", "calibration"},
    {1, "large_checkerboard_calibration", "calibration"}, {2, "rgb_calibration", "calibration"},
    {2, "ir_calibration", "calibration"}, {2, "large_checkerboard_calibration", "calibration"},
    {3, "calibration_rgb_depth", "calibration"}, {3, "calibration_ir", "calibration"},
    {3, "checkerboard_large", "calibration"},
};

// All 26 sequences of the Bonn RGB-D Dynamic dataset (24 dynamic + 2 static).
constexpr BonnEntry kBonn[] = {
    {"balloon"}, {"balloon2"}, {"balloon_tracking"}, {"balloon_tracking2"},
    {"crowd"}, {"crowd2"}, {"crowd3"}, {"kidnapping_box"}, {"kidnapping_box2"},
    {"moving_nonobstructing_box"}, {"moving_nonobstructing_box2"},
    {"moving_obstructing_box"}, {"moving_obstructing_box2"},
    {"person_tracking"}, {"person_tracking2"},
    {"placing_nonobstructing_box"}, {"placing_nonobstructing_box2"},
    {"placing_nonobstructing_box3"}, {"placing_obstructing_box"},
    {"removing_nonobstructing_box"}, {"removing_nonobstructing_box2"},
    {"removing_obstructing_box"}, {"static"}, {"static_close_far"},
    {"synchronous"}, {"synchronous2"},
};

std::vector<SequenceInfo> BuildCatalogue() {
  std::vector<SequenceInfo> out;
  for (const TumEntry& e : kTum) {
    SequenceInfo info;
    info.name = "rgbd_dataset_freiburg" + std::to_string(e.freiburg) + "_" + std::string(e.name);
    info.collection = Collection::kTum;
    info.category = e.category;
    info.archive_path = "freiburg" + std::to_string(e.freiburg) + "/" + info.name + ".tgz";
    info.size_bytes = e.size_bytes;
    info.sha256 = e.sha256;
    info.md5 = e.md5;
    out.push_back(std::move(info));
  }
  for (const BonnEntry& e : kBonn) {
    SequenceInfo info;
    info.name = "rgbd_bonn_" + std::string(e.name);
    info.collection = Collection::kBonn;
    info.category = e.name.starts_with("static") ? "static" : "dynamic";
    info.archive_path = info.name + ".zip";
    info.size_bytes = e.size_bytes;
    info.sha256 = e.sha256;
    info.md5 = e.md5;
    out.push_back(std::move(info));
  }
  return out;
}

}  // namespace

const std::vector<SequenceInfo>& Catalogue() {
  static const std::vector<SequenceInfo> catalogue = BuildCatalogue();
  return catalogue;
}

std::string_view DefaultBaseUrl(Collection collection) {
  return collection == Collection::kTum ? "https://cvg.cit.tum.de/rgbd/dataset"
                                        : "https://www.ipb.uni-bonn.de/html/projects/rgbd_dynamic2019";
}

}  // namespace dlslam::datasets
