# SPDX-License-Identifier: MIT
# Hardening: hostile-input tests of the smb tool, the libFuzzer targets (fuzz/) and the soak and
# scale programs (bench/soak/). Included by tests/CMakeLists.txt, which defines smb_add_gtest().

option(SMB_BUILD_FUZZERS "Build the libFuzzer targets in fuzz/ (needs clang++ and SMB_SANITIZE)" OFF)

if(TARGET smb_cli)
  smb_add_gtest(NAME test_hostile_files
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_hostile_files.cpp
    LIBS smb_io)
  target_compile_definitions(test_hostile_files PRIVATE
    SMB_CLI_PATH="$<TARGET_FILE:smb_cli>"
    SMB_CLI_DATA_DIR="${CMAKE_CURRENT_LIST_DIR}/data/cli")
  add_dependencies(test_hostile_files smb_cli)
endif()
if(TARGET smb_io)
  smb_add_gtest(NAME test_hostile_pair_sorter
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_hostile_pair_sorter.cpp
    LIBS smb_io)
endif()

# Every committed fuzz input (seed corpora and the regressions the fuzzers found) replayed
# through the targets' own checks, in every build, with or without clang.
if(TARGET smb_io)
  smb_add_gtest(NAME test_hostile_fuzz_inputs
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_hostile_fuzz_inputs.cpp
    LIBS smb_io)
  target_include_directories(test_hostile_fuzz_inputs PRIVATE ${PROJECT_SOURCE_DIR}/fuzz)
  target_compile_definitions(test_hostile_fuzz_inputs PRIVATE
    SMB_FUZZ_DIR="${PROJECT_SOURCE_DIR}/fuzz")
endif()

if(TARGET smb_workload)
  add_executable(smb_soak ${PROJECT_SOURCE_DIR}/bench/soak/smb_soak.cpp)
  target_link_libraries(smb_soak PRIVATE smb::smb smb_workload)
  smb_configure_target(smb_soak)
endif()
add_executable(smb_explosion ${PROJECT_SOURCE_DIR}/bench/soak/smb_explosion.cpp)
target_link_libraries(smb_explosion PRIVATE smb::smb)
smb_configure_target(smb_explosion)

if(SMB_BUILD_FUZZERS)
  add_subdirectory(${PROJECT_SOURCE_DIR}/fuzz ${PROJECT_BINARY_DIR}/fuzz)
endif()
