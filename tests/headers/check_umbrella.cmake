# Lists the headers fuzzypid/fuzzypid.hpp includes (transitively, project headers only) and fails
# if any is a robot header or lies outside the core folders.
# Usage: cmake -DCXX=<c++ compiler> -DINCLUDE_DIR=<repo>/include -P check_umbrella.cmake
set(umbrella ${INCLUDE_DIR}/fuzzypid/fuzzypid.hpp)
execute_process(COMMAND ${CXX} -std=c++17 -I${INCLUDE_DIR} -MM -x c++ ${umbrella}
                OUTPUT_VARIABLE deps ERROR_VARIABLE errors RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "could not preprocess ${umbrella}:\n${errors}")
endif()
string(REGEX REPLACE "\\\\\n" " " deps "${deps}")
string(REGEX REPLACE "^[^:]*:" "" deps "${deps}")
separate_arguments(deps UNIX_COMMAND "${deps}")

set(core_count 0)
foreach(dep IN LISTS deps)
  file(RELATIVE_PATH rel ${INCLUDE_DIR} ${dep})
  if(rel MATCHES "^fuzzypid/robot/")
    message(FATAL_ERROR "the core umbrella includes a robot header: ${rel}")
  endif()
  if(NOT rel MATCHES "^fuzzypid/([a-z_]+\\.hpp|(fuzzy|pid|supervisor)/[a-z_]+\\.hpp)$")
    message(FATAL_ERROR "the core umbrella includes a header outside the core: ${dep}")
  endif()
  math(EXPR core_count "${core_count} + 1")
endforeach()
# Positive control: the scan did see the core.
if(NOT "${deps}" MATCHES "fuzzypid/pid/pid.hpp" OR core_count LESS 5)
  message(FATAL_ERROR "dependency scan of ${umbrella} looks wrong: ${deps}")
endif()
message(STATUS "fuzzypid.hpp includes ${core_count} core headers and no robot header")
