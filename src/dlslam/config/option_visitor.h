#pragma once
// One walk over every option of the system, for every use that needs all of
// them: reading a config file, writing the defaults with their comments
// (`dlslam config dump`), recording the effective options in a report. The
// field list lives in one place (run_options.cc); each visitor does one job.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace dlslam::config {

// What a visitor is told about each option besides its value.
struct OptionInfo {
  std::string_view unit;     // "m", "px", "deg", "frames"; "" when none
  std::string_view comment;  // one line: what it does
};

class OptionVisitor {
 public:
  virtual ~OptionVisitor() = default;
  // A nested group (a module's options struct); Begin/End pair up.
  virtual void Begin(std::string_view section, std::string_view comment) = 0;
  virtual void End() = 0;
  virtual void Value(std::string_view key, bool& value, const OptionInfo& info) = 0;
  virtual void Value(std::string_view key, int& value, const OptionInfo& info) = 0;
  virtual void Value(std::string_view key, std::uint32_t& value, const OptionInfo& info) = 0;
  virtual void Value(std::string_view key, std::size_t& value, const OptionInfo& info) = 0;
  virtual void Value(std::string_view key, double& value, const OptionInfo& info) = 0;
  virtual void Value(std::string_view key, std::string& value, const OptionInfo& info) = 0;
  virtual void Value(std::string_view key, std::vector<int>& value, const OptionInfo& info) = 0;
  // One of `choices` (an enum by name).
  virtual void Choice(std::string_view key, std::string& value, const std::vector<std::string>& choices,
                      const OptionInfo& info) = 0;

  void Value(std::string_view key, std::filesystem::path& value, const OptionInfo& info) {
    std::string text = value.string();
    Value(key, text, info);
    value = text;
  }
  // An enum through its names: to_string(E) and parse(string) -> E.
  template <class E, class ToStringFn, class ParseFn>
  void Enum(std::string_view key, E& value, const std::vector<std::string>& choices, ToStringFn to_string,
            ParseFn parse, const OptionInfo& info) {
    std::string name = to_string(value);
    Choice(key, name, choices, info);
    value = parse(name);
  }
};

}  // namespace dlslam::config
