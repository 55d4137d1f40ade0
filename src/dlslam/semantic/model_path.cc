#include "dlslam/semantic/model_path.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdlib>
#include <system_error>
#include <vector>

#include "dlslam/util/check.h"

#ifndef DLSLAM_SOURCE_MODELS_DIR
#define DLSLAM_SOURCE_MODELS_DIR ""
#endif

namespace dlslam::semantic {

namespace fs = std::filesystem;

ModelSearch DefaultModelSearch() {
  ModelSearch search;
  if (const char* env = std::getenv("DLSLAM_MODEL_DIR"); env != nullptr && *env != '\0') search.env_dir = env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && exe.has_parent_path()) {
    search.installed_dir = exe.parent_path().parent_path() / "share" / "dlslam" / "models";
  }
  search.source_models_dir = DLSLAM_SOURCE_MODELS_DIR;
  return search;
}

fs::path ResolveModelPath(const fs::path& explicit_model, const std::string& file_name,
                          const ModelSearch& search) {
  std::error_code ec;
  if (!explicit_model.empty()) {
    if (!fs::is_regular_file(explicit_model, ec)) {
      throw InputError(explicit_model, 0, fs::exists(explicit_model, ec) ? "model path is not a regular file"
                                                                         : "model file not found");
    }
    return explicit_model;
  }
  DLSLAM_CHECK(!file_name.empty(), "no model file name to search for");
  std::vector<std::string> tried;
  const std::pair<const fs::path*, const char*> places[] = {
      {&search.env_dir, "$DLSLAM_MODEL_DIR"},
      {&search.installed_dir, "installed models"},
      {&search.source_models_dir, "source tree models/"}};
  for (const auto& [dir, label] : places) {
    if (dir->empty()) {
      tried.push_back(fmt::format("{} (not set)", label));
      continue;
    }
    const fs::path candidate = *dir / file_name;
    if (fs::is_regular_file(candidate, ec)) return candidate;
    tried.push_back(fmt::format("{} '{}'", label, candidate.string()));
  }
  throw Error(fmt::format("segmentation model '{}' not found; give --model FILE or set DLSLAM_MODEL_DIR. "
                          "Tried: {}",
                          file_name, fmt::join(tried, "; ")));
}

}  // namespace dlslam::semantic
