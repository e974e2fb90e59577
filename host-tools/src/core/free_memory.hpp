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

}  // namespace jacobid
