// SPDX-License-Identifier: MIT
#pragma once
// Large host-side buffers (an hour's log columns: 29 MB each) backed by transparent huge pages where the
// kernel grants them only on request (the "madvise" policy, e.g. this project's Debian machines): each page
// fault then brings in 2 MB instead of 4 KB. Filling the hour's buffers page by page cost 340 000 faults
// and 4.6 s of system time of a 15 s identification (docs/performance.md). Advice only: ignored where
// unsupported, never an error, and the contents are unchanged.
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace jacobid {

inline void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
    const auto begin = (reinterpret_cast<std::uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHuge - 1);
    if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
    (void)data, (void)bytes;
#endif
}

// The whole capacity of `v` (call it after reserve, before the elements are written).
template <class T>
void advise_huge_pages(const std::vector<T>& v) {
    advise_huge_pages(v.data(), v.capacity() * sizeof(T));
}

// A copy of [first, last) whose pages come in huge where granted: for the whole-log temporaries (a
// difference, a copy to partially sort) that are filled once and freed.
template <class T, class It>
std::vector<T> huge_vector(It first, It last) {
    std::vector<T> v;
    v.reserve(static_cast<std::size_t>(std::distance(first, last)));
    advise_huge_pages(v);
    v.assign(first, last);
    return v;
}

// `n` copies of `value`, likewise.
template <class T>
std::vector<T> huge_vector(std::size_t n, const T& value = T()) {
    std::vector<T> v;
    v.reserve(n);
    advise_huge_pages(v);
    v.assign(n, value);
    return v;
}

}  // namespace jacobid
