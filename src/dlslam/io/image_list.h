#pragma once
// The image lists of a TUM-layout sequence: rgb.txt / depth.txt
// ("timestamp path" per line) and association files
// ("t_rgb rgb/x.png t_depth depth/y.png" per line, as associate.py writes
// them). '#' comments, blank lines; paths relative to the sequence folder.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace dlslam::io {

// One image named by a list file, with where it was named (for errors).
struct ListedImage {
  double timestamp = 0.0;           // [s]
  std::filesystem::path path;       // as written: relative to the sequence folder
  std::filesystem::path list_file;  // the list that named it
  int line = 0;                     // 1-based line in list_file
};

struct ImageList {
  std::filesystem::path path;
  std::vector<std::string> comments;  // comment lines without '#'
  std::vector<ListedImage> images;    // strictly increasing timestamps
};

// Reads rgb.txt / depth.txt. Throws InputError (file:line) for a missing
// file, a line that is not "timestamp path", a timestamp that is not a finite
// number or not larger than the one before.
ImageList ReadImageList(const std::filesystem::path& path);

struct AssociatedImages {
  ListedImage rgb;
  ListedImage depth;
};

// Reads an association file. Same errors as ReadImageList; RGB timestamps
// must increase strictly.
std::vector<AssociatedImages> ReadAssociationFile(const std::filesystem::path& path);

// "depth factor N" (case-insensitive; "depth_factor: N" and "DepthMapFactor N"
// too) in any comment line, e.g. 7-Scenes' depth.txt "(depth factor 1000, ...)".
// Returns the first N > 0 found.
std::optional<double> DepthFactorFromComments(const std::vector<std::string>& comments);

}  // namespace dlslam::io
