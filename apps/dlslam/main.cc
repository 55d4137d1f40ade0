// dlslam: visual SLAM that stays accurate when people move through the scene.
// One tool, one subcommand per job (see commands.h).

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <new>
#include <string>
#include <string_view>
#include <cstdlib>
#include <exception>

#include "commands.h"
#include "dlslam/util/check.h"

namespace {

// One line, at most kMaxErrorChars: a message may quote a user's token, and
// a 100 KB argument must not become a 100 KB error line.
void PrintError(std::string text) {
  constexpr std::size_t kMaxErrorChars = 1000;
  std::replace_if(text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  if (text.size() > kMaxErrorChars) text = text.substr(0, kMaxErrorChars) + "... (cut)";
  spdlog::error("{}", text);
}

// "" (or "--out=") is never a valid value: a path would mean the current
// folder, a number zero.
void RefuseEmptyArguments(int argc, char** argv) {
  std::string command = "dlslam";  // the words before the first option
  for (int i = 1; i < argc && argv[i][0] != '-' && argv[i][0] != '\0'; ++i) command += std::string(" ") + argv[i];
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const bool empty_value = arg.size() > 2 && arg.substr(0, 2) == "--" && arg.back() == '=';
    if (arg.empty() || empty_value) {
      const std::string option = empty_value ? std::string(arg.substr(0, arg.size() - 1))
                                 : i > 1     ? std::string(argv[i - 1]).substr(0, 60)
                                             : "argument 1";
      throw dlslam::Error(fmt::format("{}: empty value (see {} --help)", option, command));
    }
  }
}

// CLI11 reports "dlslam nosuchcmd" as "A subcommand is required".
void RefuseUnknownCommand(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return;
  std::string known;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (sub->get_name() == argv[1]) return;
    known += (known.empty() ? "" : ", ") + sub->get_name();
  }
  throw dlslam::Error(fmt::format("unknown command {} (known: {}; see dlslam --help)", dlslam::Quoted(argv[1]), known));
}

// The command whose --help explains the refused arguments.
std::string HelpCommand(const CLI::App& app) {
  std::string command = "dlslam";
  for (const CLI::App* sub = &app; !sub->get_subcommands().empty();) {
    sub = sub->get_subcommands().front();
    command += " " + sub->get_name();
  }
  return command + " --help";
}

}  // namespace

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
  dlslam::app::AddConfigCommand(app);
  dlslam::app::AddInfoCommand(app);
  dlslam::app::AddSynthCommand(app);
  dlslam::app::AddEvalCommand(app);
  dlslam::app::AddDatasetCommand(app);
  dlslam::app::AddVocabCommand(app);
  dlslam::app::AddSegmentCommand(app);
  dlslam::app::AddBenchCommand(app);
  dlslam::app::AddCompositeCommand(app);

  // Every refusal is one line on stderr and exit status 1; help and
  // --version print to stdout and exit 0.
  try {
    RefuseEmptyArguments(argc, argv);
    RefuseUnknownCommand(app, argc, argv);
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --help-all, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    PrintError(fmt::format("{} (see {})", e.what(), HelpCommand(app)));
    return EXIT_FAILURE;
  } catch (const std::filesystem::filesystem_error& e) {
    // A file system call without our own check in front (a symlink loop, a
    // name too long): name the path and the system's reason.
    PrintError(fmt::format("{}: {}", dlslam::ShortPath(e.path1()), e.code().message()));
    return EXIT_FAILURE;
  } catch (const dlslam::Error& e) {
    PrintError(e.what());
    return EXIT_FAILURE;
  } catch (const std::bad_alloc&) {
    PrintError("out of memory (is an input far larger than expected?)");
    return EXIT_FAILURE;
  } catch (const std::exception& e) {
    PrintError(fmt::format("unexpected error: {}", e.what()));
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
