#pragma once
// Where the files we ship in models/ (networks, vocabularies) are found at run
// time, in this order:
//   1. an explicit path given by the user (it must exist);
//   2. $DLSLAM_MODEL_DIR/<name>, when the variable is set;
//   3. <folder of the running executable>/../share/dlslam/models/<name>
//      (the installed layout: bin/dlslam next to share/dlslam/models);
//   4. <source tree>/models/<name> (compile definition), for builds run in
//      place (build/bin/dlslam).

#include <filesystem>
#include <string_view>
#include <vector>

namespace dlslam::io {

// Throws InputError when the explicit path does not exist, or when `name` is
// in none of the default places (the message lists them).
std::filesystem::path FindModelFile(std::string_view name, const std::filesystem::path& explicit_path = {});

// The default places for `name`, in search order (2 to 4 above).
std::vector<std::filesystem::path> ModelFileCandidates(std::string_view name);

}  // namespace dlslam::io
