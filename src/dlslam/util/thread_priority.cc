#include "dlslam/util/thread_priority.h"

#include <spdlog/spdlog.h>

#include <cerrno>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace dlslam {

#if defined(__linux__)

namespace {
// On Linux, PRIO_PROCESS with a thread id sets that one thread's nice value.
id_t ThisThreadId() { return static_cast<id_t>(syscall(SYS_gettid)); }
}  // namespace

bool LowerThisThreadPriority(int nice_increment) {
  if (nice_increment <= 0 || nice_increment > 19) return nice_increment == 0;
  const int target = ThisThreadNice() + nice_increment;
  return setpriority(PRIO_PROCESS, ThisThreadId(), target > 19 ? 19 : target) == 0;
}

int ThisThreadNice() {
  errno = 0;
  const int nice = getpriority(PRIO_PROCESS, ThisThreadId());
  return errno == 0 ? nice : 0;
}

#else

bool LowerThisThreadPriority(int nice_increment) { return nice_increment == 0; }
int ThisThreadNice() { return 0; }

#endif

void LowerBackgroundPriority(int nice_increment, std::string_view thread_name) {
  if (!LowerThisThreadPriority(nice_increment)) {
    spdlog::warn("could not lower the {} thread's priority by {}: it competes with the tracker as an equal",
                 thread_name, nice_increment);
  }
}

}  // namespace dlslam
