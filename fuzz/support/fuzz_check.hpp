// SPDX-License-Identifier: MIT
#pragma once
// A property a fuzz target asserts about the parser's result. A violation is a finding like a crash:
// the message says which property failed, and abort() makes libFuzzer save the input (crash-<sha1>).
#include <cstdio>
#include <cstdlib>

#define JACOBID_FUZZ_CHECK(condition, what)                                                         \
    do {                                                                                            \
        if (!(condition)) {                                                                         \
            std::fprintf(stderr, "%s:%d: property violated: %s (%s)\n", __FILE__, __LINE__, what, \
                         #condition);                                                               \
            std::abort();                                                                           \
        }                                                                                           \
    } while (0)
