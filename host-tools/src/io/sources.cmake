# SPDX-License-Identifier: MIT
# Raw robot logs described by a YAML log format, resampled onto a uniform grid (docs/log-format.md;
# included by host-tools/CMakeLists.txt). The CLI options shared by identify, diagnose and differentiate
# go into the command line's support library (the jacobid executable and the Python module use them).
target_sources(jacobid_host_base PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/log_format.cpp
  ${CMAKE_CURRENT_LIST_DIR}/raw_log_reader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/log_text_checks.cpp
  ${CMAKE_CURRENT_LIST_DIR}/increasing_rows.cpp
  ${CMAKE_CURRENT_LIST_DIR}/distinct_inputs.cpp
  ${CMAKE_CURRENT_LIST_DIR}/resample.cpp
  ${CMAKE_CURRENT_LIST_DIR}/nonuniform_jacobi.cpp
)
target_link_libraries(jacobid_host_base PRIVATE $<BUILD_INTERFACE:jacobid_yaml>)
target_sources(jacobid_options PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../options/log_format_options.cpp)
