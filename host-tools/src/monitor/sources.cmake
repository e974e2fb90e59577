# SPDX-License-Identifier: MIT
# Contact monitoring with the identified model (`jacobid monitor`, included by host-tools/CMakeLists.txt).
target_sources(jacobid_host PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/monitor_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/external_torque_replay.cpp
  ${CMAKE_CURRENT_LIST_DIR}/contact_events.cpp
  ${CMAKE_CURRENT_LIST_DIR}/calibration.cpp
  ${CMAKE_CURRENT_LIST_DIR}/monitor_file.cpp
  ${CMAKE_CURRENT_LIST_DIR}/monitor_report.cpp
)
target_sources(jacobid PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../cli/monitor_command.cpp)
