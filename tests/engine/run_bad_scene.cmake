# Runs the scene checker on one bad scene and asserts: non-zero exit, and stderr naming the file, the
# key and what was expected. The expectation is the scene's first line: "# expect: TEXT" (TEXT must
# appear in stderr, e.g. "key 'pairs.default.rd': expected").
# With -DACCEPT=1 the scene must be accepted (exit 0) and stderr must still carry the expected warning.
# Usage: cmake -DCHECKER=exe -DSCENE=file.yaml [-DACCEPT=1] -P run_bad_scene.cmake
file(STRINGS ${SCENE} first LIMIT_COUNT 1)
string(REGEX REPLACE "^# expect: " "" expect "${first}")
if(expect STREQUAL first)
  message(FATAL_ERROR "${SCENE}: first line must be '# expect: TEXT'")
endif()
execute_process(COMMAND ${CHECKER} ${SCENE} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(ACCEPT AND NOT rc EQUAL 0)
  message(FATAL_ERROR "${SCENE}: rejected, but it should have been accepted with a warning:\n${err}")
elseif(NOT ACCEPT AND rc EQUAL 0)
  message(FATAL_ERROR "${SCENE}: accepted, but it should have been rejected")
endif()
get_filename_component(name ${SCENE} NAME)
string(FIND "${err}" "${name}:" has_file)
string(FIND "${err}" "${expect}" has_expect)
string(FIND "${err}" "expected" has_expected)
if(ACCEPT)
  set(has_expected 0)
endif()
if(has_file LESS 0 OR has_expect LESS 0 OR has_expected LESS 0)
  message(FATAL_ERROR "${SCENE}: message does not name the file, '${expect}' and what was expected:\n${err}")
endif()
message(STATUS "${name}: ${err}")
