# SPDX-License-Identifier: MIT
# Model-discrepancy diagnosis (`jacobid diagnose`, included by host-tools/CMakeLists.txt).
target_sources(jacobid_host PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/statistics.cpp
  ${CMAKE_CURRENT_LIST_DIR}/decimated_rows.cpp
  ${CMAKE_CURRENT_LIST_DIR}/blocked_grams.cpp
  ${CMAKE_CURRENT_LIST_DIR}/heldout.cpp
  ${CMAKE_CURRENT_LIST_DIR}/candidate_catalogue.cpp
  ${CMAKE_CURRENT_LIST_DIR}/selection.cpp
  ${CMAKE_CURRENT_LIST_DIR}/residual_analysis.cpp
  ${CMAKE_CURRENT_LIST_DIR}/horizon_simulation.cpp
  ${CMAKE_CURRENT_LIST_DIR}/diagnosis.cpp
  ${CMAKE_CURRENT_LIST_DIR}/diagnosis_report.cpp
  ${CMAKE_CURRENT_LIST_DIR}/diagnose_log.cpp
  ${CMAKE_CURRENT_LIST_DIR}/robot_export.cpp
)
target_sources(jacobid PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../cli/diagnose_command.cpp)
target_sources(jacobid_options PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../options/diagnose_options.cpp)
