# SPDX-License-Identifier: MIT
# Proves that smb can be consumed two ways: installed into a prefix and found with
# find_package, and added as a subproject with FetchContent. Run with cmake -P, given
# SMB_SOURCE_DIR, CONSUMER_DIR and SCRATCH_DIR (wiped first); CMAKE_CXX_COMPILER is optional.

foreach(required SMB_SOURCE_DIR CONSUMER_DIR SCRATCH_DIR)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "run_consumers.cmake needs -D${required}=...")
  endif()
endforeach()

set(compiler_args)
if(CMAKE_CXX_COMPILER)
  list(APPEND compiler_args -DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER})
endif()

function(run_step description)
  message(STATUS "consumer proof: ${description}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "consumer proof failed at: ${description} (exit ${result})")
  endif()
endfunction()

# Debug builds: the proof is about packaging, and the library compiles several times faster
# unoptimised.
file(REMOVE_RECURSE ${SCRATCH_DIR})
file(MAKE_DIRECTORY ${SCRATCH_DIR})
set(prefix ${SCRATCH_DIR}/prefix)

run_step("configure smb alone"
  ${CMAKE_COMMAND} -S ${SMB_SOURCE_DIR} -B ${SCRATCH_DIR}/smb-build
    -DCMAKE_BUILD_TYPE=Debug -DCMAKE_INSTALL_PREFIX=${prefix}
    -DSMB_BUILD_TESTS=OFF -DSMB_BUILD_TOOLS=OFF -DSMB_BUILD_BENCHMARKS=OFF
    -DSMB_BUILD_EXAMPLES=OFF -DSMB_BUILD_PYTHON=OFF
    ${compiler_args})
run_step("build smb" ${CMAKE_COMMAND} --build ${SCRATCH_DIR}/smb-build --parallel 2)
run_step("install smb" ${CMAKE_COMMAND} --install ${SCRATCH_DIR}/smb-build)

run_step("configure the find_package consumer"
  ${CMAKE_COMMAND} -S ${CONSUMER_DIR}/installed -B ${SCRATCH_DIR}/installed-build
    -DCMAKE_BUILD_TYPE=Debug -DCMAKE_PREFIX_PATH=${prefix} ${compiler_args})
run_step("build the find_package consumer"
  ${CMAKE_COMMAND} --build ${SCRATCH_DIR}/installed-build --parallel 2)
run_step("run the find_package consumer" ${SCRATCH_DIR}/installed-build/consumer)
if(EXISTS ${SCRATCH_DIR}/installed-build/bullet_consumer)
  run_step("run the find_package consumer of smb::bullet" ${SCRATCH_DIR}/installed-build/bullet_consumer)
endif()
if(EXISTS ${SCRATCH_DIR}/installed-build/bullet_dynamics_consumer)
  run_step("run the find_package consumer of smb::bullet_dynamics"
    ${SCRATCH_DIR}/installed-build/bullet_dynamics_consumer)
endif()

run_step("configure the FetchContent consumer"
  ${CMAKE_COMMAND} -S ${CONSUMER_DIR}/fetched -B ${SCRATCH_DIR}/fetched-build
    -DCMAKE_BUILD_TYPE=Debug -DSMB_SOURCE_DIR=${SMB_SOURCE_DIR}
    -DFETCHCONTENT_FULLY_DISCONNECTED=ON
    ${compiler_args})
run_step("build the FetchContent consumer"
  ${CMAKE_COMMAND} --build ${SCRATCH_DIR}/fetched-build --parallel 2)
run_step("run the FetchContent consumer" ${SCRATCH_DIR}/fetched-build/consumer)

message(STATUS "consumer proof: both consumers found the pair")
