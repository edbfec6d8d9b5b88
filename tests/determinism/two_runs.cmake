# Determinism across processes: runs the cyclone-world runner twice on the same scene,
# each writing a full trace (every body, every step, %.17g: the exact doubles) and a
# summary, and requires the two traces to be byte for byte the same, and the summaries'
# sensor events and joints (their breaks) the same (the rest of a summary holds timings).
#
#   cmake -DRUNNER=... -DSCENE=... -DWORK_DIR=... [-DSTEPS=N] -P two_runs.cmake
foreach(var RUNNER SCENE WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "two_runs.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT DEFINED STEPS)
  set(STEPS 600)
endif()

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
foreach(run first second)
  execute_process(COMMAND ${RUNNER} run ${SCENE} --steps ${STEPS} --quiet --trace ${WORK_DIR}/${run}.csv
    --summary ${WORK_DIR}/${run}.json
    RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "the ${run} run of ${SCENE} failed (${status}): ${err}")
  endif()
endforeach()
file(SIZE ${WORK_DIR}/first.csv size)
if(size LESS 1000)
  message(FATAL_ERROR "the trace of ${SCENE} is too short to compare (${size} bytes)")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK_DIR}/first.csv ${WORK_DIR}/second.csv
  RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "two runs of ${SCENE} gave different traces: ${WORK_DIR}/first.csv, ${WORK_DIR}/second.csv")
endif()
# The summaries' sensor events and joints: a member a scene's summary does not have reads
# as empty in both runs.
file(READ ${WORK_DIR}/first.json first_summary)
file(READ ${WORK_DIR}/second.json second_summary)
set(compared "")
foreach(member sensor_events joints)
  foreach(run first second)
    string(JSON ${run}_value ERROR_VARIABLE missing GET "${${run}_summary}" ${member})
    if(missing)
      set(${run}_value "")
    endif()
  endforeach()
  if(NOT first_value STREQUAL second_value)
    message(FATAL_ERROR "two runs of ${SCENE} gave different ${member}: ${WORK_DIR}/first.json, ${WORK_DIR}/second.json")
  endif()
  if(NOT first_value STREQUAL "")
    string(APPEND compared ", the same ${member}")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})
message(STATUS "two runs of ${SCENE}: ${STEPS} steps, identical traces (${size} bytes)${compared}")
