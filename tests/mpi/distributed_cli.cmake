# SPDX-License-Identifier: MIT
# `smb pairs --distributed` under mpirun writes the same bytes as the serial `smb pairs`, on a
# random scene of several frames (the paper's environment: boxes that move, appear and leave).
# Run with -DSMB=... -DMPIEXEC=... -DNP=... -DSCRATCH=... -DDIM=...
file(MAKE_DIRECTORY ${SCRATCH})
set(scene ${SCRATCH}/scene.csv)
execute_process(COMMAND ${SMB} generate --dim ${DIM} -n 3000 --steps 6 --seed ${NP}${DIM} -o ${scene}
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "smb generate failed: ${status}")
endif()
execute_process(COMMAND ${SMB} pairs --input ${scene} --output ${SCRATCH}/serial.csv RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "smb pairs failed: ${status}")
endif()
execute_process(COMMAND ${MPIEXEC} -np ${NP} --oversubscribe --allow-run-as-root
  ${SMB} pairs --distributed --input ${scene} --output ${SCRATCH}/distributed.csv RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "mpirun -np ${NP} smb pairs --distributed failed: ${status}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${SCRATCH}/serial.csv ${SCRATCH}/distributed.csv
  RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "the distributed pair CSV differs from the serial one (${SCRATCH})")
endif()
file(STRINGS ${SCRATCH}/serial.csv lines)
list(LENGTH lines line_count)
if(line_count LESS 100)
  message(FATAL_ERROR "the scene gave only ${line_count} lines of pairs: too few to compare anything")
endif()
