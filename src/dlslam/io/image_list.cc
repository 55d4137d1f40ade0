#include "dlslam/io/image_list.h"

#include <regex>

#include "dlslam/io/text_table.h"
#include "dlslam/util/check.h"

namespace dlslam::io {
namespace {

ListedImage ParseImage(const TextRow& row, std::size_t first, const std::filesystem::path& path,
                       const char* what) {
  ListedImage image;
  image.timestamp = ParseDouble(row.fields[first], path, row.line, std::string(what) + " timestamp");
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
  static const std::regex pattern(R"((depth[ _]?(map)?[ _]?factor)\s*[:=]?\s*([0-9]+(\.[0-9]*)?))",
                                  std::regex::icase);
  for (const std::string& comment : comments) {
    std::smatch match;
    if (std::regex_search(comment, match, pattern)) {
      const double factor = std::stod(match[3].str());
      if (factor > 0) return factor;
    }
  }
  return std::nullopt;
}

}  // namespace dlslam::io
