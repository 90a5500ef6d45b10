# SPDX-License-Identifier: MIT
# Unit tests of the algorithm's internals (src/): they see the private headers.
foreach(concept shell_sort axial_cut singular_regroup paper_example paper_example_pipeline id_index box_store cut_tree quantile_select cell_pairs class_members)
  if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/test_${concept}.cpp)
    smb_add_gtest(NAME test_${concept} SOURCES test_${concept}.cpp)
    target_include_directories(test_${concept} PRIVATE ${PROJECT_SOURCE_DIR}/src)
  endif()
endforeach()

# Public-API tests of pair limits and streaming.
smb_add_gtest(NAME test_pair_limit SOURCES test_pair_limit.cpp)
smb_add_gtest(NAME test_paper_memory SOURCES test_paper_memory.cpp)
smb_add_gtest(NAME test_paper_segment_rule SOURCES test_paper_segment_rule.cpp)
