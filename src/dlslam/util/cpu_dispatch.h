// DLSLAM_POPCNT_CLONES: put before a hot bit-counting function to get, on x86
// with GCC, a clone built with the POPCNT instruction, picked at load time when
// the CPU has it (several times faster than the portable bit count).
//
// Not under ThreadSanitizer: the clone's resolver is an ifunc that the dynamic
// loader runs before the sanitizer's runtime exists, and the instrumented
// resolver then crashes the program before main().
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_THREAD__)
#define DLSLAM_POPCNT_CLONES __attribute__((target_clones("popcnt", "default")))
#else
#define DLSLAM_POPCNT_CLONES
#endif
