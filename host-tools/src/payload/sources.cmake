# SPDX-License-Identifier: MIT
# Payload identification (`jacobid payload`, issue 39; included by host-tools/CMakeLists.txt).
target_sources(jacobid_host PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/payload_inertia.cpp
  ${CMAKE_CURRENT_LIST_DIR}/arm_file.cpp
  ${CMAKE_CURRENT_LIST_DIR}/time_alignment.cpp
  ${CMAKE_CURRENT_LIST_DIR}/payload_rows.cpp
  ${CMAKE_CURRENT_LIST_DIR}/payload_equations.cpp
  ${CMAKE_CURRENT_LIST_DIR}/payload_uncertainty.cpp
  ${CMAKE_CURRENT_LIST_DIR}/payload_estimate.cpp
  ${CMAKE_CURRENT_LIST_DIR}/payload_report.cpp
  ${CMAKE_CURRENT_LIST_DIR}/payload_export.cpp
)
target_sources(jacobid PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../cli/payload_command.cpp)
