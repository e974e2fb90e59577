# SPDX-License-Identifier: MIT
# Robot models and their descriptions (included by host-tools/CMakeLists.txt).
find_package(urdfdom REQUIRED)
target_sources(jacobid_host_base PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/robot_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/planar2r_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/robot_description.cpp
  ${CMAKE_CURRENT_LIST_DIR}/robot_description_yaml.cpp
  ${CMAKE_CURRENT_LIST_DIR}/controller_description.cpp
  ${CMAKE_CURRENT_LIST_DIR}/base_parameters.cpp
  ${CMAKE_CURRENT_LIST_DIR}/serial_robot_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/urdf_chain.cpp
  ${CMAKE_CURRENT_LIST_DIR}/package_uri.cpp
  ${CMAKE_CURRENT_LIST_DIR}/urdf_export.cpp
  ${CMAKE_CURRENT_LIST_DIR}/base_parameter_report.cpp
  ${CMAKE_CURRENT_LIST_DIR}/load_friction_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/presliding_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/simulated_parameters.cpp
)
# urdfdom's headers are not warning-clean under -Wshadow/-Wconversion: include them as system headers.
target_include_directories(jacobid_host_base SYSTEM PRIVATE ${urdfdom_INCLUDE_DIRS})
# Building: urdfdom_LIBRARIES, the files urdfdom-config.cmake found with find_library (sysroot-aware; its
# imported targets name /usr/lib/<triplet>/libtinyxml.so outside any sysroot, which breaks the cross build of
# the emulated board). Installed: the imported target, so that the exported jacobid::host names it and
# jacobidConfig.cmake finds it with find_dependency(urdfdom); urdf_parser lives in urdfdom_model.
target_link_libraries(jacobid_host_base PRIVATE "$<BUILD_INTERFACE:${urdfdom_LIBRARIES}>" "$<INSTALL_INTERFACE:urdfdom::urdfdom_model>")
# urdf_export edits URDF with TinyXML, the XML library urdfdom reads it with (find_library: sysroot-aware).
find_library(JACOBID_TINYXML_LIBRARY tinyxml REQUIRED)
find_path(JACOBID_TINYXML_INCLUDE_DIR tinyxml.h REQUIRED)
target_include_directories(jacobid_host_base SYSTEM PRIVATE ${JACOBID_TINYXML_INCLUDE_DIR})
target_link_libraries(jacobid_host_base PRIVATE "$<BUILD_INTERFACE:${JACOBID_TINYXML_LIBRARY}>" "$<INSTALL_INTERFACE:tinyxml>")
# Robot descriptions are read with the YAML idiom shared with the firmware (yaml/).
target_link_libraries(jacobid_host_base PRIVATE $<BUILD_INTERFACE:jacobid_yaml>)
