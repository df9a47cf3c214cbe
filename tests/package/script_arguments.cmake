# Shared by the package test scripts: fuzzypid_script_arguments(REQUIRED <var>... LISTS <var>...)
# fails unless every REQUIRED variable was passed with -D, and turns each LISTS variable back
# into a CMake list (tests/package/CMakeLists.txt passes lists with | for ;, which ctest would
# otherwise split).
function(fuzzypid_script_arguments)
  cmake_parse_arguments(ARG "" "" "REQUIRED;LISTS" ${ARGN})
  foreach(var IN LISTS ARG_REQUIRED)
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "${CMAKE_SCRIPT_MODE_FILE} needs -D${var}=...")
    endif()
  endforeach()
  foreach(var IN LISTS ARG_LISTS)
    if(DEFINED ${var})
      string(REPLACE "|" ";" value "${${var}}")
      set(${var} "${value}" PARENT_SCOPE)
    endif()
  endforeach()
endfunction()
