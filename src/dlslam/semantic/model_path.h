#pragma once
// Where the product finds its segmentation model at run time (it never
// needs ../shared): an explicit path (--model) wins; otherwise the first
// existing of $DLSLAM_MODEL_DIR/<file>, <exe dir>/../share/dlslam/models/<file>
// (an installed tree) and <source>/models/<file> (a build tree).

#include <filesystem>
#include <optional>
#include <string>

namespace dlslam::semantic {

// The folders searched, in order; empty = not available.
struct ModelSearch {
  std::filesystem::path env_dir;             // $DLSLAM_MODEL_DIR
  std::filesystem::path installed_dir;       // <dir of the executable>/../share/dlslam/models
  std::filesystem::path source_models_dir;   // the source tree's models/ (compile definition)
};

// This process's search places: the environment, /proc/self/exe and the
// source tree baked in at build time (DLSLAM_SOURCE_MODELS_DIR).
ModelSearch DefaultModelSearch();

// explicit_model non-empty: it must exist (InputError naming it otherwise).
// Else the first `file_name` found in `search`; throws dlslam::Error listing
// every place tried when none has it.
std::filesystem::path ResolveModelPath(const std::filesystem::path& explicit_model,
                                       const std::string& file_name, const ModelSearch& search);

}  // namespace dlslam::semantic
