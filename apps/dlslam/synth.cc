#include "commands.h"

namespace dlslam::app {

// Not yet built: registers nothing, so `dlslam --help` does not list it.
void AddSynthCommand(CLI::App& /*app*/) {}

}  // namespace dlslam::app
