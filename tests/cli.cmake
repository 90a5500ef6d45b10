# SPDX-License-Identifier: MIT
# Tests of the workload library, the CSV I/O and the smb tool. Included by tests/CMakeLists.txt,
# which defines smb_add_gtest().

smb_add_gtest(NAME test_dynamic_environment
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_dynamic_environment.cpp
  LIBS smb_workload)
smb_add_gtest(NAME test_environment_share
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_environment_share.cpp
  LIBS smb_workload)
smb_add_gtest(NAME test_reference_grid
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_reference_grid.cpp
  LIBS smb_workload)

# The CSV formats and the tool live in tools/smb, built only with SMB_BUILD_TOOLS.
if(TARGET smb_io)
  foreach(name test_scene_csv test_pair_csv test_cli_frame_diff test_cli_output_file)
    smb_add_gtest(NAME ${name} SOURCES ${CMAKE_CURRENT_LIST_DIR}/${name}.cpp LIBS smb_io)
  endforeach()
endif()

# End to end: the built binary on small scenes in tests/data/cli.
if(TARGET smb_cli)
  find_package(nlohmann_json REQUIRED)
  foreach(name test_cli_pairs test_cli_events test_cli_generate_run test_cli_output_targets test_cli_arguments
               test_cli_messages test_cli_join test_cli_periodic)
    smb_add_gtest(NAME ${name}
      SOURCES ${CMAKE_CURRENT_LIST_DIR}/${name}.cpp
      LIBS smb_io smb_workload nlohmann_json::nlohmann_json)
    target_compile_definitions(${name} PRIVATE
      SMB_CLI_PATH="$<TARGET_FILE:smb_cli>"
      SMB_CLI_DATA_DIR="${CMAKE_CURRENT_LIST_DIR}/data/cli"
      SMB_CLI_README="${PROJECT_SOURCE_DIR}/tools/smb/README.md")
    add_dependencies(${name} smb_cli)
  endforeach()

  # Randomised odd scenes (far, beyond the float range, tiny, mixed sizes, touching lattices,
  # one-ulp gaps; churn over frames) through the binary, against a brute force in Python
  # (standard library only), on both paths of the sweep.
  find_program(SMB_PYTHON3 python3)
  if(SMB_PYTHON3)
    foreach(lanes default four)
      set(test_name cli_pairs_random_odd_scenes_${lanes}_lanes)
      add_test(NAME ${test_name}
        COMMAND ${SMB_PYTHON3} ${PROJECT_SOURCE_DIR}/scripts/stress-pairs.py
          --smb $<TARGET_FILE:smb_cli> --trials 20 --seed $<IF:$<STREQUAL:${lanes},four>,2,1>)
      set_tests_properties(${test_name} PROPERTIES LABELS cli TIMEOUT 900)
    endforeach()
    set_tests_properties(cli_pairs_random_odd_scenes_four_lanes PROPERTIES ENVIRONMENT SMB_NO_AVX2=1)
  endif()
endif()
