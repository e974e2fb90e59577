# Warnings on for every target we own; applied with jacobid_set_warnings(target).
function(jacobid_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion)
  if(JACOBID_MARCH)
    target_compile_options(${target} PRIVATE -march=${JACOBID_MARCH})
  endif()
endfunction()
