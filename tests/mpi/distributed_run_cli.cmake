# SPDX-License-Identifier: MIT
# `smb run --distributed` under mpirun against the serial `smb run` with the same options: the
# pair counts of every step byte for byte, and the summary's heading, pairs and check verdict
# lines (the other lines are timings and the ranks' bytes). Every rank generates its own share
# of the environment; the check passes the shares around a ring.
# Run with -DSMB=... -DMPIEXEC=... -DNP=... -DSCRATCH=... -DDIM=...
file(MAKE_DIRECTORY ${SCRATCH})
# -L 0.01: up to 1 % of the boxes inserted or removed each step, so that shares change.
set(options run --dim ${DIM} -n 2000 --steps 6 -L 0.01 --seed ${NP}${DIM} --check-every 2 --no-progress)
execute_process(COMMAND ${SMB} ${options} --pair-counts ${SCRATCH}/serial-counts.csv
  OUTPUT_FILE ${SCRATCH}/serial.txt RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "smb run failed: ${status}")
endif()
execute_process(COMMAND ${MPIEXEC} -np ${NP} --oversubscribe --allow-run-as-root
  ${SMB} ${options} --distributed --pair-counts ${SCRATCH}/distributed-counts.csv
  OUTPUT_FILE ${SCRATCH}/distributed.txt RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "mpirun -np ${NP} smb run --distributed failed: ${status}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${SCRATCH}/serial-counts.csv
  ${SCRATCH}/distributed-counts.csv RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "the distributed pair counts differ from the serial ones (${SCRATCH})")
endif()

# The lines that must read the same: the heading, the pairs, and the check up to its timing.
function(deterministic_lines file result)
  file(STRINGS ${file} lines)
  list(GET lines 0 heading)
  set(kept "${heading}")
  foreach(line IN LISTS lines)
    if(line MATCHES "^  pairs per step ")
      list(APPEND kept "${line}")
    elseif(line MATCHES "^  (check +OK, [0-9]+ steps? equals? the grid reference \\(last: step [0-9]+),")
      list(APPEND kept "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  set(${result} "${kept}" PARENT_SCOPE)
endfunction()
deterministic_lines(${SCRATCH}/serial.txt serial)
deterministic_lines(${SCRATCH}/distributed.txt distributed)
list(LENGTH serial kept_count)
if(NOT kept_count EQUAL 3)
  message(FATAL_ERROR "the serial summary lacks its heading, pairs or check line: ${serial}")
endif()
if(NOT serial STREQUAL distributed)
  message(FATAL_ERROR "the summaries differ:\nserial:      ${serial}\ndistributed: ${distributed}")
endif()
file(STRINGS ${SCRATCH}/serial-counts.csv counts)
list(GET counts 1 first_step)
if(NOT first_step MATCHES "^1,[0-9][0-9][0-9]+$")
  message(FATAL_ERROR "the scene gave too few pairs to compare anything: ${first_step}")
endif()
