# Builds the API documentation with docs/Doxyfile into WORK_DIR and fails on any warning
# (the Doxyfile sets WARN_AS_ERROR; anything on stderr fails too). Skipped when doxygen
# is not installed.
#
#   cmake -DDOXYGEN=... -DSOURCE_DIR=... -DWORK_DIR=... -P doxygen_check.cmake
if(NOT DOXYGEN)
  message("doxygen is not installed: skipped (install it with scripts/deps.sh)")
  return()
endif()
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
file(WRITE ${WORK_DIR}/Doxyfile "@INCLUDE = ${SOURCE_DIR}/docs/Doxyfile\nOUTPUT_DIRECTORY = ${WORK_DIR}\n")
execute_process(COMMAND ${DOXYGEN} ${WORK_DIR}/Doxyfile WORKING_DIRECTORY ${SOURCE_DIR}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0 OR NOT err STREQUAL "")
  message(FATAL_ERROR "doxygen docs/Doxyfile failed (${status}):\n${err}${out}")
endif()
if(NOT EXISTS ${WORK_DIR}/html/index.html)
  message(FATAL_ERROR "doxygen wrote no ${WORK_DIR}/html/index.html")
endif()
message(STATUS "API documentation built without warnings: ${WORK_DIR}/html/index.html")
