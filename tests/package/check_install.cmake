cmake_minimum_required(VERSION 3.16)
# ctest script: installs the build tree into PREFIX (recreated) and checks that every part of the
# package is there: licence, core and part headers, libraries, package config, tools and data.
include(${CMAKE_CURRENT_LIST_DIR}/script_arguments.cmake)
fuzzypid_script_arguments(REQUIRED BUILD_DIR PREFIX PARTS TOOLS LISTS PARTS TOOLS)
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX}
                OUTPUT_QUIET RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "install failed (${rc})")
endif()
set(expected
  share/doc/fuzzypid/LICENSE
  include/fuzzypid/fuzzypid.hpp
  lib/cmake/fuzzypid/fuzzypidConfig.cmake
  lib/cmake/fuzzypid/fuzzypidConfigVersion.cmake
  lib/cmake/fuzzypid/fuzzypid-core-targets.cmake
  share/fuzzypid/rulebases/paper.fis
  share/fuzzypid/urdf/er50_c20.urdf
  share/fuzzypid/controllers/tuned_fuzzy.toml
  share/fuzzypid/tuning/robust.toml
  share/fuzzypid/tuning/ur5_class.toml
  share/fuzzypid/urdf/ur5_class.urdf
  share/fuzzypid/paths/ur5_deburring_contour.csv)
foreach(part IN LISTS PARTS)
  list(APPEND expected lib/cmake/fuzzypid/fuzzypid-${part}-targets.cmake
                       lib/libfuzzypid_${part}.a)
endforeach()
foreach(tool IN LISTS TOOLS)
  list(APPEND expected bin/${tool})
endforeach()
foreach(path IN LISTS expected)
  if(NOT EXISTS ${PREFIX}/${path})
    message(FATAL_ERROR "not installed: ${path}")
  endif()
endforeach()
# The installed tool runs from the prefix and finds the installed rule base.
if("fuzzypid" IN_LIST TOOLS)
  execute_process(COMMAND ${PREFIX}/bin/fuzzypid --help RESULT_VARIABLE rc OUTPUT_QUIET)
  if(rc)
    message(FATAL_ERROR "installed fuzzypid --help failed (${rc})")
  endif()
endif()
message(STATUS "installed and complete: ${PREFIX}")
