# SPDX-License-Identifier: MIT
# Warnings on for every target we own; applied with jacobid_set_warnings(target).
function(jacobid_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion)
  if(JACOBID_MARCH)
    target_compile_options(${target} PRIVATE -march=${JACOBID_MARCH})
    # GCC 12 reports -Wmaybe-uninitialized inside its own avx512fintrin.h (_mm512_undefined_*, GCC PR 105593,
    # fixed in GCC 13) wherever Eigen vectorizes with AVX-512: a false positive in a system header.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
      target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
    endif()
  endif()
endfunction()
