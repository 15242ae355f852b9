# Test helpers shared by tests/ and validation/.
set(MDPORE_TEST_ENV
    OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
    OMPI_MCA_btl_vader_single_copy_mechanism=none OMP_NUM_THREADS=1)

# mdpore_add_test(NAME name [NP ranks] [LABELS ...] [TIMEOUT s] COMMAND cmd args...)
# NP > 0 runs the command under mpiexec with that many ranks.
function(mdpore_add_test)
  cmake_parse_arguments(T "" "NAME;NP;TIMEOUT;WORKING_DIRECTORY" "COMMAND;LABELS;ENVIRONMENT" ${ARGN})
  set(cmd ${T_COMMAND})
  if(T_NP)
    set(cmd ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${T_NP} ${MPIEXEC_EXTRA_FLAGS} ${T_COMMAND})
  endif()
  if(NOT T_WORKING_DIRECTORY)
    set(T_WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  endif()
  add_test(NAME ${T_NAME} COMMAND ${cmd} WORKING_DIRECTORY ${T_WORKING_DIRECTORY})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  set_tests_properties(${T_NAME} PROPERTIES TIMEOUT ${T_TIMEOUT}
                       ENVIRONMENT "${MDPORE_TEST_ENV};${T_ENVIRONMENT}" SKIP_RETURN_CODE 77)
  if(T_NP)
    set_tests_properties(${T_NAME} PROPERTIES PROCESSORS ${T_NP})
  endif()
  if(T_LABELS)
    set_tests_properties(${T_NAME} PROPERTIES LABELS "${T_LABELS}")
  endif()
endfunction()

# mdpore_add_refusal_test(NAME name [LABELS ...] [TIMEOUT s] [ENVIRONMENT VAR=value...]
#                         EXPECT text... COMMAND cmd args...)
# A command line that must be refused: a non-zero exit (no crash, no hang past TIMEOUT, default 60 s)
# with every EXPECT text in stderr (cmake/run_cli_refusal.cmake). It runs in a folder of its own
# under the build tree. No argument or text may hold '|'.
function(mdpore_add_refusal_test)
  cmake_parse_arguments(T "" "NAME;TIMEOUT" "COMMAND;LABELS;EXPECT;ENVIRONMENT" ${ARGN})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 60)
  endif()
  string(JOIN "|" cmd ${T_COMMAND})
  string(JOIN "|" expect ${T_EXPECT})
  mdpore_add_test(NAME ${T_NAME} LABELS ${T_LABELS} TIMEOUT ${T_TIMEOUT}
                  ENVIRONMENT ${T_ENVIRONMENT}
                  COMMAND ${CMAKE_COMMAND} "-DCMD=${cmd}" "-DEXPECT=${expect}"
                          -DWORKDIR=${CMAKE_CURRENT_BINARY_DIR}/refusal_${T_NAME}
                          -P ${PROJECT_SOURCE_DIR}/cmake/run_cli_refusal.cmake)
endfunction()

# add_subdirectory() for each module folder (engine image foam flowdata upscale) that has a
# CMakeLists.txt; upscale only when PETSc is enabled. Used by tests/ and validation/.
macro(mdpore_add_module_dirs)
  foreach(sub engine image foam flowdata upscale)
    if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${sub}/CMakeLists.txt)
      if(NOT (sub STREQUAL "upscale" AND NOT MDPORE_PETSC_ENABLED))
        add_subdirectory(${sub})
      endif()
    endif()
  endforeach()
endmacro()
