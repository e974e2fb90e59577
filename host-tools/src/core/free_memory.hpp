// SPDX-License-Identifier: MIT
#pragma once
// Hands the memory freed so far back to the kernel (glibc's malloc_trim). Once glibc's mmap threshold has
// risen (it follows the largest block freed, up to 32 MB), whole-log temporaries such as the bandwidth
// estimate's per-joint copies (29 MB each for an hour at 1 kHz, one set per thread) come from the heap and
// stay resident after they are freed; the identification's fold, which follows them, then started 90 MB
// higher (docs/performance.md). No-op without glibc's allocator.
#if defined(__GLIBC__)
#include <malloc.h>
#endif

// Whether glibc's allocator is the one in use: under AddressSanitizer malloc is the sanitizer's, glibc's arenas are
// never set up by an allocation, and malloc_trim from several threads at once raced through their first set-up
// (a SEGV inside glibc's mtrim in the sanitizer build's `identify`, once in a clean-clone CI run of 2026-12-07; there
// is nothing of glibc's to trim there anyway).
#if defined(__SANITIZE_ADDRESS__)
#define JACOBID_GLIBC_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define JACOBID_GLIBC_MALLOC 0
#endif
#endif
#if !defined(JACOBID_GLIBC_MALLOC) && defined(__GLIBC__)
#define JACOBID_GLIBC_MALLOC 1
#elif !defined(JACOBID_GLIBC_MALLOC)
#define JACOBID_GLIBC_MALLOC 0
#endif

namespace jacobid {

inline void return_freed_memory() {
#if JACOBID_GLIBC_MALLOC
    (void)malloc_trim(0);
#endif
}

// Gives every block of 4 MB or more its own mapping, unmapped when it is freed, for the rest of the process:
// `identify` and `diagnose` call it before they read a log. Not the whole of jacobid: with it, `record` and
// `sim-can` beside jacobid-fw on the emulated board (tests/vm, scenario board) cost the firmware two overruns
// of 2.2-2.6 ms at start-up, twice in a row; without it, none. glibc's threshold otherwise rises with each large block freed, so the
// hour's later whole-log and per-chunk buffers came from the per-thread heaps and their freed space stayed
// resident there: the peak moved by 25 MB from run to run with the threads' timing (docs/performance.md).
// A fixed threshold turns that adjustment off. No-op without glibc's allocator.
inline void map_large_blocks() {
#if JACOBID_GLIBC_MALLOC
    (void)mallopt(M_MMAP_THRESHOLD, 4 << 20);
    // Fixing the threshold also stops the trim threshold from following it: left at 128 kB, the heap's top
    // was handed back and faulted in again around every chunk's buffers (2 s of system time per hour).
    (void)mallopt(M_TRIM_THRESHOLD, 64 << 20);
#endif
}

}  // namespace jacobid
