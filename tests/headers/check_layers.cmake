# Fails if a header of the generic layers (supervisor/, pid/, fuzzy/) includes fuzzypid/paper.hpp,
# directly or transitively, or if a header under include/fuzzypid/ declares a friend.
# Usage: cmake -DCXX=<c++ compiler> -DINCLUDE_DIR=<repo>/include -P check_layers.cmake
file(GLOB generic ${INCLUDE_DIR}/fuzzypid/supervisor/*.hpp ${INCLUDE_DIR}/fuzzypid/pid/*.hpp
     ${INCLUDE_DIR}/fuzzypid/fuzzy/*.hpp)
list(LENGTH generic count)
if(count LESS 5)
  message(FATAL_ERROR "found only ${count} headers in supervisor/, pid/, fuzzy/: ${generic}")
endif()
foreach(header IN LISTS generic)
  execute_process(COMMAND ${CXX} -std=c++17 -I${INCLUDE_DIR} -MM -x c++ ${header}
                  OUTPUT_VARIABLE deps ERROR_VARIABLE errors RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "could not preprocess ${header}:\n${errors}")
  endif()
  if(deps MATCHES "fuzzypid/paper\\.hpp")
    message(FATAL_ERROR "${header} includes fuzzypid/paper.hpp")
  endif()
endforeach()

file(GLOB_RECURSE all ${INCLUDE_DIR}/fuzzypid/*.hpp)
foreach(header IN LISTS all)
  file(STRINGS ${header} friends REGEX "(^|[^a-z_])friend[ \t]")
  if(friends)
    message(FATAL_ERROR "${header} declares a friend: ${friends}")
  endif()
endforeach()
message(STATUS "${count} headers of supervisor/, pid/, fuzzy/ without paper.hpp; no friend in include/fuzzypid/")
