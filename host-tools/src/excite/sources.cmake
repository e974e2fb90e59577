# SPDX-License-Identifier: MIT
# Excitation trajectories (jacobid excite; included by host-tools/CMakeLists.txt when NLopt is found): an
# internal library, not installed (so that jacobid::host's users do not need NLopt), linked by the command
# line and the tests.
add_library(jacobid_excite ${JACOBID_LIBRARY_KIND}
  ${CMAKE_CURRENT_LIST_DIR}/fourier_trajectory.cpp
  ${CMAKE_CURRENT_LIST_DIR}/information_criterion.cpp
  ${CMAKE_CURRENT_LIST_DIR}/periodic_lowpass.cpp
  ${CMAKE_CURRENT_LIST_DIR}/parameter_scales.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prior_file.cpp
  ${CMAKE_CURRENT_LIST_DIR}/motion_information.cpp
  ${CMAKE_CURRENT_LIST_DIR}/reference_motion.cpp
  ${CMAKE_CURRENT_LIST_DIR}/frequency_rule.cpp
  ${CMAKE_CURRENT_LIST_DIR}/regressor_derivatives.cpp
  ${CMAKE_CURRENT_LIST_DIR}/regressor_derivatives_adjoint.cpp
  ${CMAKE_CURRENT_LIST_DIR}/regressor_derivatives_automatic.cpp
  ${CMAKE_CURRENT_LIST_DIR}/identification_bandwidth.cpp
  ${CMAKE_CURRENT_LIST_DIR}/excitation_problem.cpp
  ${CMAKE_CURRENT_LIST_DIR}/excitation_design.cpp
  ${CMAKE_CURRENT_LIST_DIR}/design_checks.cpp
  ${CMAKE_CURRENT_LIST_DIR}/frame_kinematics.cpp
  ${CMAKE_CURRENT_LIST_DIR}/workspace_box.cpp
  ${CMAKE_CURRENT_LIST_DIR}/payload_target.cpp
)
# The adjoint is instantiated for every joint count (about 40 s of compile CPU): outside the unity batches, so that it
# compiles beside them instead of lengthening one.
set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/regressor_derivatives_adjoint.cpp PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
target_link_libraries(jacobid_excite PUBLIC jacobid_host PRIVATE NLopt::nlopt_cxx)
jacobid_set_warnings(jacobid_excite)
