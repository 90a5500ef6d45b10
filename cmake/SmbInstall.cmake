# SPDX-License-Identifier: MIT
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# `cmake --install` may follow a build of one target (scripts/run.sh builds the tool alone):
# the targets it installs are built first, so that it never misses a file.
set(smb_installed_targets smb)
foreach(target smb_bullet smb_mpi smb_cli)
  if(TARGET ${target})
    list(APPEND smb_installed_targets ${target})
  endif()
endforeach()
install(CODE "
  set(smb_config_arguments)
  if(CMAKE_INSTALL_CONFIG_NAME)
    set(smb_config_arguments --config \"\${CMAKE_INSTALL_CONFIG_NAME}\")
  endif()
  execute_process(
    COMMAND \"${CMAKE_COMMAND}\" --build \"${CMAKE_BINARY_DIR}\" --target ${smb_installed_targets}
            \${smb_config_arguments}
    RESULT_VARIABLE smb_build_result)
  if(NOT smb_build_result EQUAL 0)
    message(FATAL_ERROR \"building what the install needs (${smb_installed_targets}) failed\")
  endif()
")

install(TARGETS smb EXPORT smbTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(TARGET smb_bullet)
  install(TARGETS smb_bullet EXPORT smbTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(FILES ${PROJECT_SOURCE_DIR}/cmake/SmbFindBullet.cmake DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/smb)
  set(SMB_HAS_BULLET ON)
else()
  set(SMB_HAS_BULLET OFF)
endif()
if(TARGET smb_bullet_dynamics)
  install(TARGETS smb_bullet_dynamics EXPORT smbTargets)
  set(SMB_HAS_BULLET_DYNAMICS ON)
else()
  set(SMB_HAS_BULLET_DYNAMICS OFF)
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/smb DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${PROJECT_BINARY_DIR}/generated/include/smb/version.hpp
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/smb)
install(EXPORT smbTargets NAMESPACE smb:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/smb)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/smbConfig.cmake.in
  ${PROJECT_BINARY_DIR}/smbConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/smb)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/smbConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/smbConfig.cmake ${PROJECT_BINARY_DIR}/smbConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/smb)

if(SMB_BUILD_TOOLS AND TARGET smb_cli)
  install(TARGETS smb_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

# smb::mpi, where it was built (smbConfig.cmake finds MPI for it).
if(TARGET smb_mpi)
  install(TARGETS smb_mpi EXPORT smbTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
endif()
