# Tests of the workload library, the CSV I/O and the smb tool. Included by tests/CMakeLists.txt,
# which defines smb_add_gtest().

smb_add_gtest(NAME test_dynamic_environment
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_dynamic_environment.cpp
  LIBS smb_workload)
smb_add_gtest(NAME test_reference_grid
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_reference_grid.cpp
  LIBS smb_workload)
