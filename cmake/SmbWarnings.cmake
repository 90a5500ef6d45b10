# SPDX-License-Identifier: MIT
# Warnings and sanitizers are set per target (PRIVATE), never through CMAKE_CXX_FLAGS.
function(smb_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion)
  if(SMB_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

function(smb_set_sanitizers target)
  if(SMB_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

function(smb_configure_target target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  smb_set_warnings(${target})
  smb_set_sanitizers(${target})
endfunction()
