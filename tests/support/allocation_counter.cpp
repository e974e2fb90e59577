// SPDX-License-Identifier: MIT
// Interposes malloc/calloc/realloc/aligned_alloc (glibc exports the real ones as __libc_*) and the global
// operator new family, counting each call. Frees are not counted: the claim under test is "no allocation".
// Under AddressSanitizer the C allocator belongs to the sanitizer: only the operator new family is counted
// (through std::malloc, which ASan intercepts), so sanitizer runs still check C++ allocations.
#include "allocation_counter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

// gcc says __SANITIZE_ADDRESS__, clang (before 16) only __has_feature(address_sanitizer).
#if defined(__SANITIZE_ADDRESS__)
#define JACOBID_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define JACOBID_ASAN 1
#endif
#endif

#if defined(JACOBID_ASAN)
#define JACOBID_RAW_MALLOC std::malloc
#define JACOBID_RAW_MEMALIGN(alignment, n) std::aligned_alloc(alignment, ((n) + (alignment) - 1) / (alignment) * (alignment))
#else
#define JACOBID_RAW_MALLOC __libc_malloc
#define JACOBID_RAW_MEMALIGN __libc_memalign
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
}
#endif

namespace {
std::atomic<std::uint64_t> g_allocations{0};
}

std::uint64_t jacobid::test::allocation_count() noexcept { return g_allocations.load(); }

#if !defined(JACOBID_ASAN)
extern "C" void* malloc(std::size_t n) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    return __libc_malloc(n);
}
extern "C" void* calloc(std::size_t n, std::size_t m) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    return __libc_calloc(n, m);
}
extern "C" void* realloc(void* p, std::size_t n) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    return __libc_realloc(p, n);
}
extern "C" void* aligned_alloc(std::size_t alignment, std::size_t n) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    return __libc_memalign(alignment, n);
}
#endif

void* operator new(std::size_t n) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = JACOBID_RAW_MALLOC(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    return JACOBID_RAW_MALLOC(n ? n : 1);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void* operator new(std::size_t n, std::align_val_t a) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = JACOBID_RAW_MEMALIGN(static_cast<std::size_t>(a), n ? n : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n, std::align_val_t a) { return operator new(n, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
