# SPDX-License-Identifier: MIT
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(smb_installed_targets smb)
if(TARGET smb_mpi)
  list(APPEND smb_installed_targets smb_mpi)
endif()
install(TARGETS ${smb_installed_targets} EXPORT smbTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
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
