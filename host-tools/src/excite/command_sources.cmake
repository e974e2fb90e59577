# SPDX-License-Identifier: MIT
# jacobid excite's command and options, added to the command line once it is defined (host-tools/CMakeLists.txt; the
# library, sources.cmake, is defined before everything else).
target_sources(jacobid PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src/cli/excite_command.cpp ${CMAKE_CURRENT_SOURCE_DIR}/src/cli/excite_prediction.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/src/options/excite_options.cpp)
target_link_libraries(jacobid PRIVATE jacobid_excite)
target_compile_definitions(jacobid PRIVATE JACOBID_WITH_NLOPT=1)
