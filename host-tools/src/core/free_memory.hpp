// SPDX-License-Identifier: MIT
#pragma once
// Hands the memory freed so far back to the kernel (glibc's malloc_trim). Once glibc's mmap threshold has
// risen (it follows the largest block freed, up to 32 MB), whole-log temporaries such as the bandwidth
// estimate's per-joint copies (29 MB each for an hour at 1 kHz, one set per thread) come from the heap and
// stay resident after they are freed; the identification's fold, which follows them, then started 90 MB
// higher (docs/performance.md). No-op without glibc.
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace jacobid {

inline void return_freed_memory() {
#if defined(__GLIBC__)
    (void)malloc_trim(0);
#endif
}

// Gives every block of 4 MB or more its own mapping, unmapped when it is freed, for the rest of the process:
// `identify` and `diagnose` call it before they read a log. Not the whole of jacobid: with it, `record` and
// `sim-can` beside jacobid-fw on the emulated board (tests/vm, scenario board) cost the firmware two overruns
// of 2.2-2.6 ms at start-up, twice in a row; without it, none. glibc's threshold otherwise rises with each large block freed, so the
// hour's later whole-log and per-chunk buffers came from the per-thread heaps and their freed space stayed
// resident there: the peak moved by 25 MB from run to run with the threads' timing (docs/performance.md).
// A fixed threshold turns that adjustment off. No-op without glibc.
inline void map_large_blocks() {
#if defined(__GLIBC__)
    (void)mallopt(M_MMAP_THRESHOLD, 4 << 20);
    // Fixing the threshold also stops the trim threshold from following it: left at 128 kB, the heap's top
    // was handed back and faulted in again around every chunk's buffers (2 s of system time per hour).
    (void)mallopt(M_TRIM_THRESHOLD, 64 << 20);
#endif
}

}  // namespace jacobid
