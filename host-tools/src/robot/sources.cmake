# Robot models and their descriptions (included by host-tools/CMakeLists.txt).
target_sources(jacobid_host PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/robot_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/planar2r_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/robot_description.cpp
)
