cmake_minimum_required(VERSION 3.16)
# ctest script: configure, build and run one downstream project.
#   CONSUMER_DIR  the project          WORK_DIR  its build tree (recreated)
#   CONFIGURE_ARGS  extra -D arguments (;-list)   RUN_ARGS  arguments of the consumer (;-list)
#   EXPECT_NO_INSTALL  if set, `cmake --install` of the consumer (which installs nothing of its
#                      own) must leave its prefix empty: the vendored library adds no install rule
include(${CMAKE_CURRENT_LIST_DIR}/script_arguments.cmake)
fuzzypid_script_arguments(REQUIRED CONSUMER_DIR WORK_DIR LISTS CONFIGURE_ARGS RUN_ARGS)
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR} -G Ninja
                        -DCMAKE_BUILD_TYPE=Release ${CONFIGURE_ARGS}
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer configure failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR} --target consumer RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer build failed (${rc})")
endif()
execute_process(COMMAND ${WORK_DIR}/consumer ${RUN_ARGS} RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer run failed (${rc})")
endif()
if(EXPECT_NO_INSTALL)
  set(prefix ${WORK_DIR}/install-prefix)
  execute_process(COMMAND ${CMAKE_COMMAND} --install ${WORK_DIR} --prefix ${prefix}
                  RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "consumer install failed (${rc})")
  endif()
  file(GLOB_RECURSE installed LIST_DIRECTORIES false ${prefix}/*)
  if(installed)
    list(LENGTH installed count)
    list(GET installed 0 first)
    message(FATAL_ERROR "the vendored library installed ${count} files (first: ${first}); "
                        "FUZZYPID_INSTALL should be off below another project")
  endif()
endif()
