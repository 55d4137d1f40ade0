// `dlslam config dump` and `dlslam config check FILE`.

#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>

#include "commands.h"
#include "dlslam/config/config_file.h"

namespace dlslam::app {

void AddConfigCommand(CLI::App& app) {
  CLI::App* config = app.add_subcommand("config", "Every option of every module in one YAML file");
  config->require_subcommand(1);
  CLI::App* dump = config->add_subcommand(
      "dump", "Print every option with its default, unit and comment, as a valid file for dlslam run --config");
  auto from = std::make_shared<std::filesystem::path>();
  dump->add_option("--from", *from, "Print the options of this file instead (defaults for what it leaves out)");
  dump->callback([from] {
    config::RunOptions options;
    if (!from->empty()) config::LoadConfig(*from, &options);
    std::fputs(config::DumpConfig(options).c_str(), stdout);
  });
  CLI::App* check = config->add_subcommand("check", "Check a config file: unknown keys, types, ranges");
  auto file = std::make_shared<std::filesystem::path>();
  check->add_option("file", *file, "Config file")->required();
  check->callback([file] {
    config::RunOptions options;
    config::LoadConfig(*file, &options);
    spdlog::info("{}: every key known, every value in range", file->string());
  });
}

}  // namespace dlslam::app
