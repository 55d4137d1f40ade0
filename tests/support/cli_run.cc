#include "tests/support/cli_run.h"

#include <sys/wait.h>

#include <cstdio>

namespace dlslam::testing {

std::string Quoted(const std::filesystem::path& p) {
  // Appended piecewise: "'" + s + "'" trips a GCC 12 -Wrestrict false positive.
  std::string quoted(1, '\'');
  quoted.append(p.string()).push_back('\'');
  return quoted;
}

CliRun RunShell(const std::string& command) {
  CliRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[4096];
  for (std::size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) run.output.append(buffer, n);
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace dlslam::testing
