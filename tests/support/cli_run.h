#pragma once
// Runs a command line through the shell, as a user would, for tests of the
// `dlslam` CLI: exit code and captured output.

#include <filesystem>
#include <string>

namespace dlslam::testing {

struct CliRun {
  int exit_code = -1;  // -1: the command could not be started or was killed
  std::string output;  // stdout (add "2>&1" to the command for stderr too)
};

// `p` in single quotes for the shell.
std::string Quoted(const std::filesystem::path& p);

// popen(command) to the end.
CliRun RunShell(const std::string& command);

// A TCP port on 127.0.0.1 that was free a moment ago (bound to port 0, then
// released), for a server the test starts.
int FreeTcpPort();

}  // namespace dlslam::testing
