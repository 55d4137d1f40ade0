// Name lookup over the catalogue: full names, short forms, close matches.

#include "dlslam/datasets/catalogue.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "dlslam/util/check.h"

namespace dlslam::datasets {
namespace {

constexpr std::string_view kTumPrefix = "rgbd_dataset_freiburg";
constexpr std::string_view kBonnPrefix = "rgbd_bonn_";

std::string Lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Maps any accepted spelling onto the full name form (which may not exist).
std::string Canonical(std::string_view raw) {
  std::string s = Lower(raw);
  while (!s.empty() && (s.back() == '/' || std::isspace(static_cast<unsigned char>(s.back())))) {
    s.pop_back();
  }
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.erase(0, 1);
  for (std::string_view ext : {".tgz", ".zip"}) {
    if (s.ends_with(ext)) s.resize(s.size() - ext.size());
  }
  if (s.starts_with(kTumPrefix) || s.starts_with(kBonnPrefix)) return s;
  for (std::string_view bonn : {"bonn/", "bonn_"}) {
    if (s.starts_with(bonn)) return std::string(kBonnPrefix) + s.substr(bonn.size());
  }
  // freiburgN_x, freiburgN/x, frN/x, frN_x
  for (std::string_view fr : {"freiburg", "fr"}) {
    if (s.size() > fr.size() + 2 && s.starts_with(fr) && std::isdigit(static_cast<unsigned char>(s[fr.size()])) &&
        (s[fr.size() + 1] == '_' || s[fr.size() + 1] == '/')) {
      return std::string(kTumPrefix) + s[fr.size()] + "_" + s.substr(fr.size() + 2);
    }
  }
  return s;
}

// The part of a full name after its collection prefix ("walking_xyz", "crowd").
std::string_view Tail(std::string_view full) {
  if (full.starts_with(kTumPrefix) && full.size() > kTumPrefix.size() + 2) {
    return full.substr(kTumPrefix.size() + 2);
  }
  if (full.starts_with(kBonnPrefix)) return full.substr(kBonnPrefix.size());
  return full;
}

}  // namespace

std::string_view CollectionName(Collection collection) {
  return collection == Collection::kTum ? "tum" : "bonn";
}

std::string ShortName(const SequenceInfo& info) {
  if (info.collection == Collection::kBonn) return "bonn/" + std::string(Tail(info.name));
  return fmt::format("fr{}/{}", info.name[kTumPrefix.size()], Tail(info.name));
}

std::string ArchiveFileName(const SequenceInfo& info) {
  const auto slash = info.archive_path.rfind('/');
  return slash == std::string::npos ? info.archive_path : info.archive_path.substr(slash + 1);
}

std::string ArchiveUrl(const SequenceInfo& info, std::string_view base_url) {
  std::string base(base_url.empty() ? DefaultBaseUrl(info.collection) : base_url);
  while (!base.empty() && base.back() == '/') base.pop_back();
  return base + "/" + info.archive_path;
}

std::string CatalogueJson() {
  nlohmann::json out = nlohmann::json::array();
  const auto or_null = [](const std::string& s) { return s.empty() ? nlohmann::json() : nlohmann::json(s); };
  for (const SequenceInfo& info : Catalogue()) {
    out.push_back({{"name", info.name},
                   {"short_name", ShortName(info)},
                   {"collection", CollectionName(info.collection)},
                   {"category", info.category},
                   {"url", ArchiveUrl(info, "")},
                   {"size_bytes", info.size_bytes > 0 ? nlohmann::json(info.size_bytes) : nlohmann::json()},
                   {"sha256", or_null(info.sha256)},
                   {"md5", or_null(info.md5)}});
  }
  return out.dump(2);
}

const SequenceInfo* LookupSequence(std::string_view name) {
  const std::string canonical = Canonical(name);
  for (const SequenceInfo& info : Catalogue()) {
    if (info.name == canonical) return &info;
  }
  return nullptr;
}

std::vector<std::string> CloseMatches(std::string_view name, std::size_t max_count) {
  const std::string canonical = Canonical(name);
  const std::string tail(Tail(canonical));
  // (not a substring match, distance, catalogue index) ascending.
  std::vector<std::tuple<bool, std::size_t, std::size_t>> scored;
  const auto& catalogue = Catalogue();
  for (std::size_t i = 0; i < catalogue.size(); ++i) {
    const std::string_view other = Tail(catalogue[i].name);
    const bool substring = tail.size() >= 3 && other.find(tail) != std::string_view::npos;
    const std::size_t distance =
        std::min(EditDistance(canonical, catalogue[i].name), EditDistance(tail, other));
    if (substring || distance <= std::max<std::size_t>(2, tail.size() / 3)) {
      scored.emplace_back(!substring, distance, i);
    }
  }
  std::sort(scored.begin(), scored.end());
  std::vector<std::string> out;
  for (const auto& [not_substring, distance, index] : scored) {
    if (out.size() == max_count) break;
    out.push_back(ShortName(catalogue[index]));
  }
  return out;
}

const SequenceInfo& FindSequence(std::string_view name) {
  if (const SequenceInfo* info = LookupSequence(name)) return *info;
  const std::vector<std::string> close = CloseMatches(name);
  if (close.empty()) {
    throw Error(fmt::format("unknown sequence '{}' (see `dlslam dataset list`)", name));
  }
  throw Error(fmt::format("unknown sequence '{}'; did you mean: {}? (see `dlslam dataset list`)",
                          name, fmt::join(close, ", ")));
}

}  // namespace dlslam::datasets
