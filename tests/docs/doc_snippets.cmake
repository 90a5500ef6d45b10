# SPDX-License-Identifier: MIT
# The C++ snippets of the README and docs/, compiled with the build (not linked: they are
# fragments of a reader's program, tests/docs/doc_snippet_context.hpp declares the rest), so that
# a snippet that drifts from the API fails the build. Included by tests/CMakeLists.txt. The pages
# are listed when CMake configures: a page that gains its first snippet needs a reconfigure.
find_program(SMB_SNIPPET_PYTHON3 NAMES python3)
if(NOT SMB_SNIPPET_PYTHON3)
  message(STATUS "smb: no python3, the docs' C++ snippets are not compiled")
  return()
endif()

file(GLOB smb_doc_pages ${PROJECT_SOURCE_DIR}/docs/*.md)
set(smb_snippet_sources)
foreach(page ${PROJECT_SOURCE_DIR}/README.md ${smb_doc_pages})
  file(STRINGS ${page} fences REGEX "^```cpp")
  if(NOT fences)
    continue()
  endif()
  get_filename_component(name ${page} NAME_WE)
  file(RELATIVE_PATH relative ${PROJECT_SOURCE_DIR} ${page})
  set(out ${CMAKE_CURRENT_BINARY_DIR}/doc_snippets/${name}.cpp)
  add_custom_command(OUTPUT ${out}
    COMMAND ${SMB_SNIPPET_PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/extract_snippets.py ${page} ${out}
    DEPENDS ${page} ${CMAKE_CURRENT_LIST_DIR}/extract_snippets.py ${CMAKE_CURRENT_LIST_DIR}/markdown_blocks.py
    COMMENT "Extracting the C++ snippets of ${relative}"
    VERBATIM)
  list(APPEND smb_snippet_sources ${out})
endforeach()

add_library(smb_doc_snippets OBJECT ${smb_snippet_sources})
target_include_directories(smb_doc_snippets PRIVATE ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(smb_doc_snippets PRIVATE smb::smb)
target_compile_features(smb_doc_snippets PRIVATE cxx_std_20)
# Compiled only to be checked: unoptimised, and without the project's warnings (a snippet names
# a reader's variables that shadow the context's).
target_compile_options(smb_doc_snippets PRIVATE -O0)
if(TARGET smb_bullet_dynamics)
  target_link_libraries(smb_doc_snippets PRIVATE smb::bullet_dynamics)
  target_compile_definitions(smb_doc_snippets PRIVATE SMB_SNIPPETS_BULLET=1)
endif()
if(TARGET smb_mpi)
  target_link_libraries(smb_doc_snippets PRIVATE smb::mpi)
  target_compile_definitions(smb_doc_snippets PRIVATE SMB_SNIPPETS_MPI=1)
endif()
# The build compiles them; this test says so in the test list, and rebuilds them if a page
# changed since.
add_test(NAME doc_snippets_compile COMMAND ${CMAKE_COMMAND} --build ${CMAKE_BINARY_DIR} --target smb_doc_snippets)
set_tests_properties(doc_snippets_compile PROPERTIES LABELS docs TIMEOUT 600)

# The shell snippets: each smb command run on a tiny scene in a scratch folder, each script,
# binary, option, target and CMake option they name checked against the project (a block marked
# <!-- not run: reason --> passes over the commands the check does not know).
if(TARGET smb_cli)
  add_test(NAME doc_snippets_shell
    COMMAND ${SMB_SNIPPET_PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check_shell_snippets.py --smb $<TARGET_FILE:smb_cli>
      --source-dir ${PROJECT_SOURCE_DIR} --build-dir ${CMAKE_BINARY_DIR})
  set_tests_properties(doc_snippets_shell PROPERTIES LABELS docs TIMEOUT 120)
endif()
