#pragma once
// The map file (.dlmap), little-endian, versioned, checksummed like .dlv:
//
//   offset  size  field
//        0     8  magic "DLSLAMMP"
//        8     4  version (1)
//       12     4  reserved (0)
//       16     8  payload bytes p
//       24     p  payload: camera (name, size, intrinsics, distortion, depth
//                 factor, bf), scale pyramid, next ids; keyframes (id,
//                 timestamp, pose, parent, keypoints with depth and octave,
//                 descriptors, map point per keypoint, covisibility, loop
//                 edges); map points (id, position, descriptor, normal,
//                 distances, reference and first keyframe, culling
//                 counters, observations); culled keyframes (parent, pose)
//   24+p       4  CRC-32 (zlib's) of every byte before it
//
// Bag-of-words vectors are not stored: they are recomputed from the
// descriptors with whatever vocabulary the loading system uses (~1 ms per
// keyframe). Saving the same map twice gives the same bytes; load then
// save gives the bytes loaded.
//
// Every defect (missing file, wrong magic, other version, truncated, bad
// checksum, counts that disagree, ids that refer to nothing) is an
// InputError naming the file and the byte offset where it shows.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "dlslam/data/camera.h"
#include "dlslam/data/frame.h"
#include "dlslam/map/map.h"

namespace dlslam {

// 2 adds the anchors of maps not merged yet (Map::SetAnchor); version 1
// files (no anchors) are still read.
inline constexpr std::uint32_t kMapFileVersion = 2;

struct MapFileHeader {
  CameraIntrinsics camera;  // the camera the map was made with
  ScalePyramid pyramid;     // the ORB pyramid of its keypoints
};

std::string SerializeMap(const MapContents& contents, const MapFileHeader& header);
// Parses bytes read from `file` (named in errors) into `map`, which must be
// empty. Throws InputError (the map stays empty).
MapFileHeader ParseMap(std::string_view bytes, const std::filesystem::path& file, Map* map);

// Writes atomically (a failed write leaves an existing file untouched).
void SaveMap(const Map& map, const MapFileHeader& header, const std::filesystem::path& file);
MapFileHeader LoadMap(const std::filesystem::path& file, Map* map);

}  // namespace dlslam
