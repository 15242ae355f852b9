# MDPORE_SANITIZE: AddressSanitizer + UndefinedBehaviorSanitizer on every C target (CUDA off: nvcc
# device code cannot be instrumented). MDPORE_FUZZ: libFuzzer targets in tests/fuzz (clang only;
# implies MDPORE_SANITIZE and adds coverage instrumentation, -fsanitize=fuzzer-no-link, to the
# libraries). docs/fuzzing.md.
option(MDPORE_SANITIZE "ASan+UBSan build of the C targets (CUDA off)" OFF)
option(MDPORE_FUZZ "libFuzzer targets and their ctests (clang; implies MDPORE_SANITIZE)" OFF)
if(MDPORE_FUZZ)
  if(NOT CMAKE_C_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "MDPORE_FUZZ=ON needs clang (libFuzzer): configure with CC=clang "
                        "(got ${CMAKE_C_COMPILER_ID})")
  endif()
  set(MDPORE_SANITIZE ON CACHE BOOL "" FORCE)
endif()
if(MDPORE_SANITIZE)
  if(NOT MDPORE_CUDA STREQUAL "OFF")
    message(STATUS "mdpore: MDPORE_SANITIZE=ON turns MDPORE_CUDA off")
    set(MDPORE_CUDA OFF CACHE STRING "CUDA backend (AUTO|ON|OFF)" FORCE)
  endif()
  # -fno-sanitize-recover: an undefined-behaviour report aborts like an ASan one (tests and fuzzers
  # see it as a failure instead of a line on stderr).
  set(_san -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  foreach(f ${_san})
    add_compile_options($<$<COMPILE_LANGUAGE:C>:${f}>)
  endforeach()
  add_link_options(-fsanitize=address,undefined)
  if(MDPORE_FUZZ)
    add_compile_options($<$<COMPILE_LANGUAGE:C>:-fsanitize=fuzzer-no-link>)
  endif()
  message(STATUS "mdpore: ASan+UBSan on (fuzz targets: ${MDPORE_FUZZ})")
endif()
