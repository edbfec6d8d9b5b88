# cyclone::core is Eigen only: a program that links it alone (core_tests) must not need
# FCL, libccd or Qhull at run time, and the target must not name them.
# Called with -DBINARY=<core_tests> -DLINKS=<file with cyclone_core's link libraries>.
file(READ "${LINKS}" links)
if(links MATCHES "fcl|ccd|[Qq]hull")
  message(FATAL_ERROR "cyclone_core links ${links}: it must link Eigen only")
endif()
find_program(READELF readelf REQUIRED)
execute_process(COMMAND ${READELF} -d "${BINARY}" OUTPUT_VARIABLE dynamic RESULT_VARIABLE failed)
if(failed OR NOT dynamic MATCHES "NEEDED")
  message(FATAL_ERROR "readelf -d ${BINARY} gave no dependencies (${failed})")
endif()
if(dynamic MATCHES "libfcl|libccd|libqhull")
  message(FATAL_ERROR "${BINARY}, linked with cyclone::core alone, needs FCL, libccd or Qhull:\n${dynamic}")
endif()
message(STATUS "core_tests needs none of FCL, libccd, Qhull")
