#include "dlslam/config/config_file.h"

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "dlslam/io/file_util.h"
#include "dlslam/util/check.h"

namespace dlslam::config {

namespace {

constexpr std::uintmax_t kMaxConfigBytes = 1u << 20;

int Line(const YAML::Node& node) { return node.Mark().is_null() ? 0 : node.Mark().line + 1; }

// The value of key `path` at `node` in `file`, read strictly: the whole token.
[[noreturn]] void Fail(const std::filesystem::path& file, const YAML::Node& node, const std::string& path,
                       const std::string& problem) {
  throw InputError(file, Line(node), "{}: {}", path, problem);
}

std::string Scalar(const std::filesystem::path& file, const YAML::Node& node, const std::string& path,
                   const char* expected) {
  if (!node.IsScalar()) Fail(file, node, path, fmt::format("expected {}, got a list or section", expected));
  return node.Scalar();
}

template <class T>
T ParseWhole(const std::filesystem::path& file, const YAML::Node& node, const std::string& path) {
  std::string s = Scalar(file, node, path, "a whole number");
  if (!s.empty() && s.front() == '+') s.erase(0, 1);
  T v{};
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || error != std::errc() || end != s.data() + s.size()) {
    Fail(file, node, path,
         fmt::format("expected a whole number in [{}, {}], got {}", std::numeric_limits<T>::min(),
                     std::numeric_limits<T>::max(), Quoted(node.Scalar())));
  }
  return v;
}

double ParseFinite(const std::filesystem::path& file, const YAML::Node& node, const std::string& path) {
  std::string s = Scalar(file, node, path, "a number");
  if (!s.empty() && s.front() == '+') s.erase(0, 1);
  double v = 0;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || error != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) {
    Fail(file, node, path, fmt::format("expected a finite number, got {}", Quoted(node.Scalar())));
  }
  return v;
}

YAML::Node LoadYaml(const std::filesystem::path& file) {
  const std::string text = io::ReadFileBytes(file, kMaxConfigBytes, "a config file");
  try {
    return YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    throw InputError(file, e.mark.is_null() ? 0 : e.mark.line + 1,
                     "malformed YAML: lists or maps nested deeper than {} levels", e.depth());
  } catch (const YAML::Exception& e) {
    throw InputError(file, e.mark.is_null() ? 0 : e.mark.line + 1, "malformed YAML: {}", e.msg);
  }
}

bool IsSettingsKey(const std::string& key) { return key.find('.') != std::string::npos || key == "DepthMapFactor" || key == "ThDepth" || key == "File.version"; }

// Sets the options from the YAML, in visiting order, the first `limit` keys found only.
class Loader final : public OptionVisitor {
 public:
  Loader(const std::filesystem::path& file, const YAML::Node& root, std::size_t limit)
      : file_(file), limit_(limit) {
    stack_.push_back({root, ""});
  }

  void Begin(std::string_view section, std::string_view) override {
    const std::optional<YAML::Node> node = Find(section);
    if (node && !node->IsMap() && !node->IsNull()) {
      throw InputError(file_, Line(*node), "{}: expected a section of 'key: value' lines", Path(section));
    }
    stack_.push_back({node && node->IsMap() ? node : std::nullopt, Path(section)});
  }
  void End() override { stack_.pop_back(); }

  void Value(std::string_view key, bool& value, const OptionInfo&) override {
    Apply(key, [&](const YAML::Node& n, const std::string& path) {
      const std::string s = Scalar(n, path, "true or false");
      if (s == "true" || s == "True" || s == "TRUE") {
        value = true;
      } else if (s == "false" || s == "False" || s == "FALSE") {
        value = false;
      } else {
        Fail(n, path, fmt::format("expected true or false, got {}", Quoted(s)));
      }
    });
  }
  void Value(std::string_view key, int& value, const OptionInfo&) override { Whole(key, value); }
  void Value(std::string_view key, std::uint32_t& value, const OptionInfo&) override { Whole(key, value); }
  void Value(std::string_view key, std::size_t& value, const OptionInfo&) override { Whole(key, value); }
  void Value(std::string_view key, double& value, const OptionInfo&) override {
    Apply(key, [&](const YAML::Node& n, const std::string& path) { value = ParseFinite(file_, n, path); });
  }
  void Value(std::string_view key, std::string& value, const OptionInfo&) override {
    Apply(key, [&](const YAML::Node& n, const std::string& path) { value = Scalar(n, path, "text"); });
  }
  void Value(std::string_view key, std::vector<int>& value, const OptionInfo&) override {
    Apply(key, [&](const YAML::Node& n, const std::string& path) {
      if (!n.IsSequence()) Fail(n, path, "expected a list of whole numbers, e.g. [1, 2]");
      std::vector<int> out;
      for (const YAML::Node& item : n) out.push_back(ParseWhole<int>(file_, item, path));
      value = out;
    });
  }
  void Choice(std::string_view key, std::string& value, const std::vector<std::string>& choices,
              const OptionInfo&) override {
    Apply(key, [&](const YAML::Node& n, const std::string& path) {
      const std::string s = Scalar(n, path, "a name");
      if (std::find(choices.begin(), choices.end(), s) == choices.end()) {
        std::string list;
        for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
        Fail(n, path, fmt::format("{} is not one of {}", Quoted(s), list));
      }
      value = s;
    });
  }

  // Keys of the file that no option took, with their lines.
  void CheckAllUsed(const YAML::Node& root, const std::vector<std::string>& known) const {
    CheckUsed(root, "", known);
  }
  std::size_t applied() const { return applied_; }
  // The key and line of the i-th value applied (0-based).
  const std::pair<std::string, int>& applied_key(std::size_t i) const { return applied_keys_.at(i); }

 private:
  struct Level {
    std::optional<YAML::Node> node;  // nullopt: the section is not in the file
    std::string path;
  };

  std::string Path(std::string_view key) const {
    return stack_.back().path.empty() ? std::string(key) : stack_.back().path + "." + std::string(key);
  }
  std::optional<YAML::Node> Find(std::string_view key) {
    const std::optional<YAML::Node>& map = stack_.back().node;
    if (!map || !map->IsMap()) return std::nullopt;
    std::optional<YAML::Node> found;
    for (const auto& entry : *map) {
      if (entry.first.IsScalar() && entry.first.Scalar() == key) found = entry.second;
    }
    if (found) used_.insert(Path(key));
    return found;
  }
  void Apply(std::string_view key, const std::function<void(const YAML::Node&, const std::string&)>& set) {
    const std::optional<YAML::Node> node = Find(key);
    if (!node || applied_ >= limit_) return;
    ++applied_;
    applied_keys_.emplace_back(Path(key), Line(*node));
    set(*node, Path(key));
  }
  [[noreturn]] void Fail(const YAML::Node& node, const std::string& path, const std::string& problem) const {
    config::Fail(file_, node, path, problem);
  }
  std::string Scalar(const YAML::Node& node, const std::string& path, const char* expected) const {
    return config::Scalar(file_, node, path, expected);
  }
  template <class T>
  void Whole(std::string_view key, T& value) {
    Apply(key, [&](const YAML::Node& n, const std::string& path) { value = ParseWhole<T>(file_, n, path); });
  }
  void CheckUsed(const YAML::Node& map, const std::string& prefix, const std::vector<std::string>& known) const {
    if (!map || !map.IsMap()) return;
    std::map<std::string, int> seen;
    for (const auto& entry : map) {
      if (!entry.first.IsScalar()) throw InputError(file_, Line(entry.first), "a key must be a name");
      const std::string& key = entry.first.Scalar();
      if (const auto [it, added] = seen.emplace(key, Line(entry.first)); !added) {
        throw InputError(file_, Line(entry.first), "key {} given twice (first on line {})",
                         Quoted(prefix + key), it->second);
      }
      if (prefix.empty() && IsSettingsKey(key)) continue;  // the camera reader's
      const std::string path = prefix + key;
      if (!used_.count(path)) {
        std::string best;
        std::size_t best_distance = 4;  // only close misspellings are suggested
        for (const std::string& k : known) {
          const std::size_t d = EditDistance(path, k);
          if (d < best_distance) {
            best_distance = d;
            best = k;
          }
        }
        throw InputError(file_, Line(entry.first), "unknown key {}{}", Quoted(path),
                         best.empty() ? std::string(" (dlslam config dump lists them all)")
                                      : fmt::format("; did you mean {}?", Quoted(best)));
      }
      if (entry.second.IsMap()) CheckUsed(entry.second, path + ".", known);
    }
  }

  const std::filesystem::path& file_;
  std::size_t limit_;
  std::vector<Level> stack_;
  std::set<std::string> used_;
  std::size_t applied_ = 0;
  std::vector<std::pair<std::string, int>> applied_keys_;
};

// Every key path, for suggestions.
class KeyLister final : public OptionVisitor {
 public:
  void Begin(std::string_view section, std::string_view) override {
    prefix_.push_back(Path(section));
    keys_.push_back(prefix_.back());
  }
  void End() override { prefix_.pop_back(); }
  void Value(std::string_view k, bool&, const OptionInfo&) override { keys_.push_back(Path(k)); }
  void Value(std::string_view k, int&, const OptionInfo&) override { keys_.push_back(Path(k)); }
  void Value(std::string_view k, std::uint32_t&, const OptionInfo&) override { keys_.push_back(Path(k)); }
  void Value(std::string_view k, std::size_t&, const OptionInfo&) override { keys_.push_back(Path(k)); }
  void Value(std::string_view k, double&, const OptionInfo&) override { keys_.push_back(Path(k)); }
  void Value(std::string_view k, std::string&, const OptionInfo&) override { keys_.push_back(Path(k)); }
  void Value(std::string_view k, std::vector<int>&, const OptionInfo&) override { keys_.push_back(Path(k)); }
  void Choice(std::string_view k, std::string&, const std::vector<std::string>&, const OptionInfo&) override {
    keys_.push_back(Path(k));
  }
  const std::vector<std::string>& keys() const { return keys_; }

 private:
  std::string Path(std::string_view key) const {
    return prefix_.empty() ? std::string(key) : prefix_.back() + "." + std::string(key);
  }
  std::vector<std::string> prefix_;
  std::vector<std::string> keys_;
};

std::string Number(double v) { return fmt::format("{}", v); }

// YAML text with a comment per key.
class Dumper final : public OptionVisitor {
 public:
  void Begin(std::string_view section, std::string_view comment) override {
    out_ += fmt::format("{}{}:  # {}\n", Indent(), section, comment);
    ++depth_;
  }
  void End() override { --depth_; }
  void Value(std::string_view k, bool& v, const OptionInfo& i) override { Line(k, v ? "true" : "false", i); }
  void Value(std::string_view k, int& v, const OptionInfo& i) override { Line(k, std::to_string(v), i); }
  void Value(std::string_view k, std::uint32_t& v, const OptionInfo& i) override { Line(k, std::to_string(v), i); }
  void Value(std::string_view k, std::size_t& v, const OptionInfo& i) override { Line(k, std::to_string(v), i); }
  void Value(std::string_view k, double& v, const OptionInfo& i) override { Line(k, Number(v), i); }
  void Value(std::string_view k, std::string& v, const OptionInfo& i) override {
    YAML::Emitter e;
    e << YAML::DoubleQuoted << v;
    Line(k, e.c_str(), i);
  }
  void Value(std::string_view k, std::vector<int>& v, const OptionInfo& i) override {
    std::string list;
    for (int x : v) list += (list.empty() ? "" : ", ") + std::to_string(x);
    Line(k, "[" + list + "]", i);
  }
  void Choice(std::string_view k, std::string& v, const std::vector<std::string>& choices, const OptionInfo& i) override {
    std::string list;
    for (const std::string& c : choices) list += (list.empty() ? "" : " | ") + c;
    Line(k, v, {i.unit, fmt::format("{} ({})", i.comment, list)});
  }
  const std::string& text() const { return out_; }

 private:
  std::string Indent() const { return std::string(2 * static_cast<std::size_t>(depth_), ' '); }
  void Line(std::string_view key, const std::string& value, const OptionInfo& info) {
    out_ += fmt::format("{}{}: {}  # {}{}\n", Indent(), key, value, info.unit.empty() ? "" : fmt::format("[{}] ", info.unit),
                        info.comment);
  }
  std::string out_;
  int depth_ = 0;
};

class JsonWriter final : public OptionVisitor {
 public:
  JsonWriter() { stack_.push_back({"", nlohmann::ordered_json::object()}); }
  void Begin(std::string_view section, std::string_view) override {
    stack_.push_back({std::string(section), nlohmann::ordered_json::object()});
  }
  void End() override {
    Level done = std::move(stack_.back());
    stack_.pop_back();
    stack_.back().json[done.name] = std::move(done.json);
  }
  void Value(std::string_view k, bool& v, const OptionInfo&) override { Set(k, v); }
  void Value(std::string_view k, int& v, const OptionInfo&) override { Set(k, v); }
  void Value(std::string_view k, std::uint32_t& v, const OptionInfo&) override { Set(k, v); }
  void Value(std::string_view k, std::size_t& v, const OptionInfo&) override { Set(k, v); }
  void Value(std::string_view k, double& v, const OptionInfo&) override { Set(k, v); }
  void Value(std::string_view k, std::string& v, const OptionInfo&) override { Set(k, v); }
  void Value(std::string_view k, std::vector<int>& v, const OptionInfo&) override { Set(k, v); }
  void Choice(std::string_view k, std::string& v, const std::vector<std::string>&, const OptionInfo&) override {
    Set(k, v);
  }
  nlohmann::ordered_json Result() const { return stack_.front().json; }

 private:
  struct Level {
    std::string name;
    nlohmann::ordered_json json;
  };
  template <class T>
  void Set(std::string_view key, const T& v) {
    stack_.back().json[std::string(key)] = v;
  }
  std::vector<Level> stack_;
};

// ORB-SLAM3's extractor keys, applied to orb (its values mean the same).
void ApplyOrbSlam3Extractor(const std::filesystem::path& file, const YAML::Node& root, features::OrbOptions* orb) {
  const auto whole = [&](const char* key, int* value) {
    if (const YAML::Node node = root[key]) *value = ParseWhole<int>(file, node, key);
  };
  whole("ORBextractor.nFeatures", &orb->n_features);
  whole("ORBextractor.nLevels", &orb->n_levels);
  whole("ORBextractor.iniThFAST", &orb->fast_threshold_initial);
  whole("ORBextractor.minThFAST", &orb->fast_threshold_min);
  if (const YAML::Node node = root["ORBextractor.scaleFactor"]) {
    orb->scale_factor = ParseFinite(file, node, "ORBextractor.scaleFactor");
  }
}

}  // namespace

void LoadConfig(const std::filesystem::path& file, RunOptions* options) {
  DLSLAM_CHECK(options != nullptr);
  const YAML::Node root = LoadYaml(file);
  if (root.IsNull()) throw InputError(file, 0, "no options in the file (only comments?)");
  if (!root.IsMap()) throw InputError(file, Line(root), "the top level must be 'key: value' lines and sections");
  RunOptions probe;
  KeyLister lister;
  VisitOptions(probe, lister);
  const RunOptions start = *options;
  RunOptions loaded = start;
  // ORB-SLAM3's extractor keys first: our own orb section, if also given, wins.
  ApplyOrbSlam3Extractor(file, root, &loaded.system.orb);
  Loader loader(file, root, std::numeric_limits<std::size_t>::max());
  VisitOptions(loaded, loader);
  loader.CheckAllUsed(root, lister.keys());
  try {
    loaded.Check();
  } catch (const Error& failed) {
    // The first key after which the options stop passing names the line.
    for (std::size_t n = 1; n <= loader.applied(); ++n) {
      RunOptions prefix = start;
      ApplyOrbSlam3Extractor(file, root, &prefix.system.orb);
      Loader partial(file, root, n);
      VisitOptions(prefix, partial);
      try {
        prefix.Check();
      } catch (const Error& e) {
        const auto& [key, line] = loader.applied_key(n - 1);
        throw InputError(file, line, "{}: out of range: {}", key, e.what());
      }
    }
    throw InputError(file, 0, "the options are inconsistent: {}", failed.what());
  }
  *options = loaded;
}

std::string DumpConfig(const RunOptions& options) {
  RunOptions copy = options;
  Dumper dumper;
  VisitOptions(copy, dumper);
  return "# DLSLAM options, every one with its value (dlslam config dump). Use with dlslam run --config FILE;\n"
         "# flags given on the command line override the file. ORB-SLAM3 settings keys (Camera.fx, ...) may\n"
         "# be added at the top level for the camera.\n" +
         dumper.text();
}

nlohmann::ordered_json ConfigJson(const RunOptions& options) {
  RunOptions copy = options;
  JsonWriter writer;
  VisitOptions(copy, writer);
  return writer.Result();
}

bool HasCameraKeys(const std::filesystem::path& file) {
  const YAML::Node root = LoadYaml(file);
  if (!root.IsMap()) return false;
  for (const auto& entry : root) {
    if (entry.first.IsScalar() && entry.first.Scalar().rfind("Camera", 0) == 0) return true;
  }
  return false;
}

}  // namespace dlslam::config
