// dlslam: visual SLAM that stays accurate when people move through the scene.
// One tool, one subcommand per job (see commands.h).

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <exception>
#include <iostream>

#include "commands.h"
#include "dlslam/util/check.h"

int main(int argc, char** argv) {
  CLI::App app{"dlslam: RGB-D SLAM for dynamic scenes (semantic + multi-view geometry)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "dlslam 0.1.0");
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Print debug messages");
  app.parse_complete_callback([&] {
    spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::info);
  });
  // Results go to stdout, every log line, warning and error to stderr, so
  // that `> result.json` captures only the result.
  spdlog::set_default_logger(spdlog::stderr_color_mt("dlslam"));
  spdlog::set_pattern("[%l] %v");

  dlslam::app::AddDemoCommand(app);
  dlslam::app::AddRunCommand(app);
  dlslam::app::AddInfoCommand(app);
  dlslam::app::AddSynthCommand(app);
  dlslam::app::AddEvalCommand(app);
  dlslam::app::AddDatasetCommand(app);
  dlslam::app::AddVocabCommand(app);
  dlslam::app::AddSegmentCommand(app);
  dlslam::app::AddBenchCommand(app);
  dlslam::app::AddCompositeCommand(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const dlslam::Error& e) {
    spdlog::error("{}", e.what());
    return EXIT_FAILURE;
  } catch (const std::exception& e) {
    spdlog::error("unexpected error: {}", e.what());
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
