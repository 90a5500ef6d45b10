# SPDX-License-Identifier: MIT
# Smoke test of the Section 4 reproduction (scripts/reproduce.py, scripts/plot-reproduction.py):
# the smoke mode (N / 500, two timed steps, every run checked against the grid reference) must
# write the three CSVs with rows, and the plots when numpy and matplotlib are there.
#
# Included by tests/CMakeLists.txt, this file registers the test; run with `cmake -P`, it is the
# test. The full and quick modes are not run here (docs/reproduction.md).

if(CMAKE_SCRIPT_MODE_FILE)
  foreach(required PYTHON SMB REPO OUT)
    if(NOT DEFINED ${required})
      message(FATAL_ERROR "reproduction.cmake: -D${required}=... is required")
    endif()
  endforeach()
  file(REMOVE_RECURSE "${OUT}")
  execute_process(
    COMMAND "${PYTHON}" "${REPO}/scripts/reproduce.py" --mode smoke --check --smb "${SMB}" --out "${OUT}"
    RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "reproduce.py --mode smoke failed: ${status}")
  endif()
  foreach(section 4.1 4.2 4.3)
    set(table "${OUT}/smoke-${section}.csv")
    if(NOT EXISTS "${table}")
      message(FATAL_ERROR "missing ${table}")
    endif()
    file(STRINGS "${table}" lines)
    list(LENGTH lines line_count)
    list(GET lines 0 header)
    if(line_count LESS 3 OR NOT header MATCHES "^experiment,case,dim,boxes,")
      message(FATAL_ERROR "${table}: expected a header and rows, got ${line_count} line(s)")
    endif()
    if(lines MATCHES "MISMATCH")
      message(FATAL_ERROR "${table}: a run differs from the grid reference")
    endif()
  endforeach()
  if(PLOT)
    execute_process(
      COMMAND "${PYTHON}" "${REPO}/scripts/plot-reproduction.py" --dir "${OUT}" --mode smoke
      RESULT_VARIABLE status OUTPUT_QUIET)
    if(NOT status EQUAL 0)
      message(FATAL_ERROR "plot-reproduction.py failed: ${status}")
    endif()
    foreach(figure fig06-time-vs-n fig07-correlation fig08-memory-vs-n fig09-time-vs-density
                   fig10-memory-vs-side fig11-time-vs-size-ratio fig12-memory-vs-size-ratio)
      if(NOT EXISTS "${OUT}/smoke-${figure}.png")
        message(FATAL_ERROR "missing ${OUT}/smoke-${figure}.png")
      endif()
    endforeach()
  endif()
  return()
endif()

if(NOT TARGET smb_cli)
  return()
endif()
# Debian's interpreter first: it is the one with numpy and matplotlib.
find_program(SMB_REPRODUCTION_PYTHON NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
find_program(SMB_REPRODUCTION_PYTHON NAMES python3)
if(NOT SMB_REPRODUCTION_PYTHON)
  message(STATUS "reproduction smoke test skipped: no python3")
  return()
endif()
execute_process(COMMAND "${SMB_REPRODUCTION_PYTHON}" -c "import numpy, matplotlib"
                RESULT_VARIABLE smb_reproduction_plot_status OUTPUT_QUIET ERROR_QUIET)
if(smb_reproduction_plot_status EQUAL 0)
  set(smb_reproduction_plot ON)
else()
  set(smb_reproduction_plot OFF)
endif()

add_test(NAME reproduction_smoke
  COMMAND ${CMAKE_COMMAND}
    -DPYTHON=${SMB_REPRODUCTION_PYTHON}
    -DSMB=$<TARGET_FILE:smb_cli>
    -DREPO=${PROJECT_SOURCE_DIR}
    -DOUT=${CMAKE_CURRENT_BINARY_DIR}/reproduction-smoke
    -DPLOT=${smb_reproduction_plot}
    -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(reproduction_smoke PROPERTIES LABELS "reproduction;smoke" TIMEOUT 300)
