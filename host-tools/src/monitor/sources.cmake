# SPDX-License-Identifier: MIT
# Contact monitoring with the identified model (`jacobid monitor`, included by host-tools/CMakeLists.txt).
# The model and the monitor YAML readers sit in jacobid_host_base: jacobid-fw reads its fw.yaml `monitor:`
# files with them (jacobid_firmware_monitor below) without the identification.
target_sources(jacobid_host_base PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/monitor_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/monitor_file.cpp
)
target_link_libraries(jacobid_host_base PRIVATE $<BUILD_INTERFACE:jacobid_yaml>)
target_sources(jacobid_host PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/external_torque_replay.cpp
  ${CMAKE_CURRENT_LIST_DIR}/contact_events.cpp
  ${CMAKE_CURRENT_LIST_DIR}/calibration.cpp
  ${CMAKE_CURRENT_LIST_DIR}/monitor_report.cpp
)
target_sources(jacobid PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../cli/monitor_command.cpp)
# fw.yaml `monitor:` -> firmware::MonitorModel (docs/firmware.md, "Contact monitor"): only with the firmware.
if(TARGET jacobid_firmware)
  add_library(jacobid_firmware_monitor STATIC ${CMAKE_CURRENT_LIST_DIR}/firmware_monitor_model.cpp)
  target_link_libraries(jacobid_firmware_monitor PUBLIC jacobid_host_base jacobid_fwconfig)
  jacobid_set_warnings(jacobid_firmware_monitor)
  target_link_libraries(jacobid-fw PRIVATE jacobid_firmware_monitor)
  target_compile_definitions(jacobid-fw PRIVATE JACOBID_FW_MONITOR=1)
endif()
