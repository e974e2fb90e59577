# SPDX-License-Identifier: MIT
# Closed-loop simulation (included by host-tools/CMakeLists.txt).
target_sources(jacobid_host_base PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/quintic_trajectory.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tabulated_trajectory.cpp
  ${CMAKE_CURRENT_LIST_DIR}/reference_checks.cpp
  ${CMAKE_CURRENT_LIST_DIR}/measurement.cpp
  ${CMAKE_CURRENT_LIST_DIR}/closed_loop.cpp
  ${CMAKE_CURRENT_LIST_DIR}/simulator.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dahl_friction.cpp
  ${CMAKE_CURRENT_LIST_DIR}/can_player.cpp
  ${CMAKE_CURRENT_LIST_DIR}/command_follower.cpp
  ${CMAKE_CURRENT_LIST_DIR}/effect_terms.cpp
  ${CMAKE_CURRENT_LIST_DIR}/effect_spec.cpp
  ${CMAKE_CURRENT_LIST_DIR}/external_torque.cpp
  ${CMAKE_CURRENT_LIST_DIR}/augmented_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/torque_delay_line.cpp
)
