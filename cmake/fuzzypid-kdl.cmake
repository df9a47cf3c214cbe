# Debian's orocos_kdl package config sets variables but exports no imported target: wrap them in
# `fuzzypid_orocos_kdl`. Used by the build (src/robot/CMakeLists.txt) and by the installed package
# config, whose exported robot library names this target as a link-only dependency.
if(NOT TARGET fuzzypid_orocos_kdl)
  add_library(fuzzypid_orocos_kdl INTERFACE IMPORTED)
  find_library(FUZZYPID_OROCOS_KDL_LIBRARY NAMES ${orocos_kdl_LIBRARIES} REQUIRED
               HINTS ${orocos_kdl_LIBRARY_DIRS})
  target_link_libraries(fuzzypid_orocos_kdl INTERFACE ${FUZZYPID_OROCOS_KDL_LIBRARY})
  target_include_directories(fuzzypid_orocos_kdl SYSTEM INTERFACE ${orocos_kdl_INCLUDE_DIRS})
endif()
