#include "dlslam/io/model_file.h"

#include <cstdlib>
#include <string>
#include <system_error>

#include "dlslam/util/check.h"

#ifndef DLSLAM_SOURCE_MODELS_DIR
#error "DLSLAM_SOURCE_MODELS_DIR must name the source tree's models/ folder"
#endif

namespace dlslam::io {

std::vector<std::filesystem::path> ModelFileCandidates(std::string_view name) {
  std::vector<std::filesystem::path> candidates;
  if (const char* dir = std::getenv("DLSLAM_MODEL_DIR"); dir != nullptr && *dir != '\0') {
    candidates.push_back(std::filesystem::path(dir) / name);
  }
  std::error_code ec;
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec && executable.has_parent_path()) {
    candidates.push_back(executable.parent_path() / ".." / "share" / "dlslam" / "models" / name);
  }
  candidates.push_back(std::filesystem::path(DLSLAM_SOURCE_MODELS_DIR) / name);
  return candidates;
}

std::filesystem::path FindModelFile(std::string_view name, const std::filesystem::path& explicit_path) {
  if (!explicit_path.empty()) {
    if (!std::filesystem::is_regular_file(explicit_path)) {
      throw InputError(explicit_path, 0, std::filesystem::exists(explicit_path) ? "not a regular file" : "file not found");
    }
    return explicit_path;
  }
  std::string tried;
  for (const std::filesystem::path& candidate : ModelFileCandidates(name)) {
    if (std::filesystem::is_regular_file(candidate)) return candidate.lexically_normal();
    tried += fmt::format("{}'{}'", tried.empty() ? "" : ", ", candidate.lexically_normal().string());
  }
  throw InputError(std::string(name), 0, "model file not found (looked in {}{}); pass its path explicitly (--model) or set DLSLAM_MODEL_DIR",
                   tried, std::getenv("DLSLAM_MODEL_DIR") ? "" : "; DLSLAM_MODEL_DIR not set");
}

}  // namespace dlslam::io
