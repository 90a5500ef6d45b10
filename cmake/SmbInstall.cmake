# SPDX-License-Identifier: MIT
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

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
