# Runs one command line that must be refused and asserts: it exits with a non-zero status (not a
# signal: a crash fails the test), within the test's timeout (a hang fails it), and its stderr holds
# every expected text (the file, the option or key, what was expected).
# Usage: cmake "-DCMD=exe|arg|..." "-DEXPECT=text|text..." [-DWORKDIR=dir] -P run_cli_refusal.cmake
# ('|' separates the arguments and the texts: none of them may hold one). Registered through
# mdpore_add_refusal_test (MdporeTesting.cmake).
if(NOT CMD OR NOT EXPECT)
  message(FATAL_ERROR "run_cli_refusal.cmake needs -DCMD and -DEXPECT")
endif()
string(REPLACE "|" ";" CMD "${CMD}")
string(REPLACE "|" ";" EXPECT "${EXPECT}")
if(WORKDIR)
  file(MAKE_DIRECTORY ${WORKDIR})
  set(wd WORKING_DIRECTORY ${WORKDIR})
endif()
execute_process(COMMAND ${CMD} ${wd} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc MATCHES "^[0-9]+$")
  message(FATAL_ERROR "crashed (${rc}):\n${err}")
elseif(rc EQUAL 0)
  message(FATAL_ERROR "accepted, but it should have been refused:\n${out}\n${err}")
endif()
foreach(text ${EXPECT})
  string(FIND "${err}" "${text}" at)
  if(at LESS 0)
    message(FATAL_ERROR "exit ${rc}, but stderr does not hold '${text}':\n${err}")
  endif()
endforeach()
message(STATUS "refused (exit ${rc}): ${err}")
