#pragma once
// Strict checks for numeric command-line values. CLI11 alone reads
// "--max-frames -1" into a size_t as 2^64 - 1 and "18446744073709551616" as
// "all frames"; these read the whole token, refuse signs, overflow, inf and
// NaN, and say the accepted range.
//
//   cmd->add_option("--max-frames", n, "...")->check(WholeNumber(0, 1e9));

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>

#include <fmt/format.h>

namespace dlslam::app {

// An integer in [low, high], written in decimal without a sign when low >= 0.
inline CLI::Validator WholeNumber(std::int64_t low, std::int64_t high) {
  return CLI::Validator(
      [low, high](std::string& text) -> std::string {
        std::int64_t value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
            value < low || value > high) {
          return fmt::format("expected a whole number in {}..{}, got '{}'", low, high,
                             text.substr(0, 40));
        }
        return {};
      },
      fmt::format("INT in {}..{}", low, high));
}

// A finite real in [low, high].
inline CLI::Validator RealNumber(double low, double high) {
  return CLI::Validator(
      [low, high](std::string& text) -> std::string {
        double value = 0;
        const char* begin = text.data() + (!text.empty() && text[0] == '+');
        const auto [end, error] = std::from_chars(begin, text.data() + text.size(), value);
        if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
            !std::isfinite(value) || value < low || value > high) {
          return fmt::format("expected a number in [{}, {}], got '{}'", low, high, text.substr(0, 40));
        }
        return {};
      },
      fmt::format("NUMBER in [{}, {}]", low, high));
}

// The long names ("--mode", ...) of the options given to `cmd` on the command
// line: what overrides a --config file.
inline std::set<std::string> GivenFlags(const CLI::App& cmd) {
  std::set<std::string> given;
  for (const CLI::Option* option : cmd.get_options()) {
    if (option->count() == 0) continue;
    for (const std::string& name : option->get_lnames()) given.insert("--" + name);
  }
  return given;
}

}  // namespace dlslam::app
