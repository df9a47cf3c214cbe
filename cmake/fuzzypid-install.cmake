# Installation of the package's parts. The package is one CMake config, `fuzzypid`, with the
# header-only core always loaded and each compiled part a component:
#   find_package(fuzzypid CONFIG REQUIRED COMPONENTS robot rulefile sim)
# A part is a target exported as fuzzypid::<part> from its own export set, its public headers
# (include/fuzzypid/<part>/) and a small script that finds its dependencies first. With
# FUZZYPID_INSTALL off both functions generate no install rule.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(FUZZYPID_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/fuzzypid)

# fuzzypid_install_part(<target> <part> [PARTS <part>...] [PACKAGES "<find_package args>"...]
#                       [SCRIPTS <file>...])
#   PARTS     other parts this one links publicly or privately (loaded first by the config)
#   PACKAGES  find_dependency() argument lists, one quoted string each
#   SCRIPTS   CMake files installed beside the config and included after the packages are found
#             (e.g. the KDL wrapper target)
function(fuzzypid_install_part target part)
  cmake_parse_arguments(ARG "" "" "PARTS;PACKAGES;SCRIPTS" ${ARGN})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${part})
  if(NOT FUZZYPID_INSTALL)
    return()
  endif()
  install(TARGETS ${target} EXPORT fuzzypid-${part}-targets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(EXPORT fuzzypid-${part}-targets NAMESPACE fuzzypid::
          DESTINATION ${FUZZYPID_INSTALL_CMAKEDIR})
  if(IS_DIRECTORY ${PROJECT_SOURCE_DIR}/include/fuzzypid/${part})
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/fuzzypid/${part}
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/fuzzypid)
  endif()
  set(deps "# Generated: what fuzzypid::${part} needs before its targets load.\n")
  string(APPEND deps "set(fuzzypid_${part}_PARTS ${ARG_PARTS})\n")
  foreach(pkg IN LISTS ARG_PACKAGES)
    string(APPEND deps "find_dependency(${pkg})\n")
  endforeach()
  foreach(script IN LISTS ARG_SCRIPTS)
    get_filename_component(name ${script} NAME)
    install(FILES ${script} DESTINATION ${FUZZYPID_INSTALL_CMAKEDIR})
    string(APPEND deps "include(\"\${CMAKE_CURRENT_LIST_DIR}/${name}\")\n")
  endforeach()
  file(WRITE ${PROJECT_BINARY_DIR}/fuzzypid-${part}-dependencies.cmake "${deps}")
  install(FILES ${PROJECT_BINARY_DIR}/fuzzypid-${part}-dependencies.cmake
          DESTINATION ${FUZZYPID_INSTALL_CMAKEDIR})
  set_property(GLOBAL APPEND PROPERTY FUZZYPID_INSTALLED_PARTS ${part})
endfunction()

# The core, the package config and the data; called once at the end of the top-level file.
function(fuzzypid_install_package)
  if(NOT FUZZYPID_INSTALL)
    return()
  endif()
  # Core headers: the umbrella and top-level headers plus the core's folders. Compiled parts
  # install their own folders (fuzzypid_install_part).
  file(GLOB core_headers ${PROJECT_SOURCE_DIR}/include/fuzzypid/*.hpp)
  install(FILES ${core_headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/fuzzypid)
  foreach(dir supervisor fuzzy pid)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/fuzzypid/${dir}
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/fuzzypid)
  endforeach()
  install(TARGETS fuzzypid EXPORT fuzzypid-core-targets)
  install(EXPORT fuzzypid-core-targets NAMESPACE fuzzypid::
          DESTINATION ${FUZZYPID_INSTALL_CMAKEDIR})

  get_property(FUZZYPID_INSTALLED_PARTS GLOBAL PROPERTY FUZZYPID_INSTALLED_PARTS)
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/fuzzypidConfig.cmake.in
    ${PROJECT_BINARY_DIR}/fuzzypidConfig.cmake INSTALL_DESTINATION ${FUZZYPID_INSTALL_CMAKEDIR})
  # Compiled parts make the package architecture dependent.
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/fuzzypidConfigVersion.cmake
    COMPATIBILITY SameMajorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/fuzzypidConfig.cmake
                ${PROJECT_BINARY_DIR}/fuzzypidConfigVersion.cmake
          DESTINATION ${FUZZYPID_INSTALL_CMAKEDIR})

  # Data the tools and libraries look for under share/fuzzypid/, and the licence.
  foreach(dir urdf rulebases controllers tuning paths)
    if(IS_DIRECTORY ${PROJECT_SOURCE_DIR}/${dir})
      install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/ DESTINATION ${CMAKE_INSTALL_DATADIR}/fuzzypid/${dir})
    endif()
  endforeach()
  install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/README.md
          DESTINATION ${CMAKE_INSTALL_DOCDIR})
endfunction()
