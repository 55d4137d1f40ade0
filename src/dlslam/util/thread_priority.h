#pragma once
// Background threads (local mapping and loop closing by default; each
// thread-owning module has a `thread_nice` option) run at a lower CPU
// priority than the tracker, so that on a machine with fewer free cores than
// busy threads the tracker gets a core the moment a frame comes and the
// background work fills the time in between (on 2 cores the network alone
// keeps one busy). Linux: a per-thread nice value; elsewhere a no-op.

#include <string_view>

namespace dlslam {

// Lowers the calling thread's priority by `nice_increment` (0..19; 0 leaves
// it). Raising priority needs privileges and is not offered. Returns false
// (and changes nothing) where the platform has no per-thread priority or
// refuses; the caller logs and carries on: priority is an optimisation.
bool LowerThisThreadPriority(int nice_increment);

// LowerThisThreadPriority for a background thread at its start: a refusal
// is logged (a warning naming `thread_name`), never thrown.
void LowerBackgroundPriority(int nice_increment, std::string_view thread_name);

// The calling thread's nice value (Linux; 0 elsewhere). For tests and logs.
int ThisThreadNice();

}  // namespace dlslam
