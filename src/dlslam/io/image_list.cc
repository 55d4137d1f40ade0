#include "dlslam/io/image_list.h"

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "dlslam/io/text_table.h"
#include "dlslam/util/check.h"

namespace dlslam::io {
namespace {

ListedImage ParseImage(const TextRow& row, std::size_t first, const std::filesystem::path& path,
                       const char* what) {
  ListedImage image;
  image.timestamp =
      ParseDouble(row.fields[first], path, row.line, std::string(what) + " timestamp");
  image.path = row.fields[first + 1];
  image.list_file = path;
  image.line = row.line;
  return image;
}

void CheckIncreasing(const ListedImage* previous, const ListedImage& image, const char* what) {
  if (previous != nullptr && !(image.timestamp > previous->timestamp)) {
    throw InputError(image.list_file, image.line,
                     "{} timestamp {:.6f} is not larger than {:.6f} on line {} "
                     "(the list must be sorted by time, without duplicates)",
                     what, image.timestamp, previous->timestamp, previous->line);
  }
}

}  // namespace

ImageList ReadImageList(const std::filesystem::path& path) {
  const TextTable table = ReadTextTable(path);
  ImageList list;
  list.path = path;
  list.comments = table.comments;
  for (const TextRow& row : table.rows) {
    if (row.fields.size() != 2) {
      throw InputError(path, row.line, "expected 'timestamp path', got {} fields",
                       row.fields.size());
    }
    ListedImage image = ParseImage(row, 0, path, "image");
    CheckIncreasing(list.images.empty() ? nullptr : &list.images.back(), image, "image");
    list.images.push_back(std::move(image));
  }
  return list;
}

std::vector<AssociatedImages> ReadAssociationFile(const std::filesystem::path& path) {
  const TextTable table = ReadTextTable(path);
  std::vector<AssociatedImages> pairs;
  for (const TextRow& row : table.rows) {
    if (row.fields.size() != 4) {
      throw InputError(path, row.line,
                       "expected 't_rgb rgb_path t_depth depth_path', got {} fields",
                       row.fields.size());
    }
    AssociatedImages pair{ParseImage(row, 0, path, "rgb"), ParseImage(row, 2, path, "depth")};
    CheckIncreasing(pairs.empty() ? nullptr : &pairs.back().rgb, pair.rgb, "rgb");
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

std::optional<double> DepthFactorFromComments(const std::vector<std::string>& comments) {
  static const char* const kKeys[] = {"depth factor", "depth_factor", "depthmapfactor",
                                      "depth map factor", "depth_map_factor"};
  for (const std::string& comment : comments) {
    std::string text = comment;
    for (char& ch : text) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    for (const std::string key : kKeys) {
      for (auto pos = text.find(key); pos != std::string::npos; pos = text.find(key, pos + 1)) {
        const auto value = text.find_first_not_of(" \t:=", pos + key.size());
        if (value == std::string::npos) continue;
        const char* begin = text.c_str() + value;
        char* end = nullptr;
        const double factor = std::strtod(begin, &end);
        if (end != begin && std::isfinite(factor) && factor > 0) return factor;
      }
    }
  }
  return std::nullopt;
}

}  // namespace dlslam::io
