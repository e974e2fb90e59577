// SPDX-License-Identifier: MIT
#pragma once
// Counts every heap allocation of the process (global operator new and the C allocator), so tests can
// prove that a real-time path allocates nothing. Link tests/support/allocation_counter.cpp.
#include <cstdint>

namespace jacobid::test {

// Total number of allocation calls since the process started.
std::uint64_t allocation_count() noexcept;

}  // namespace jacobid::test
