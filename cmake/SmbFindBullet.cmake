# SPDX-License-Identifier: MIT
# Finds Bullet's collision library (and its dynamics, when present) and defines the imported
# targets SmbBullet::Collision and SmbBullet::Dynamics. Debian's libbullet-dev ships a
# BulletConfig.cmake whose paths are relative to nothing, so the parts are looked up one by one.
# Included by the build and by the installed smbConfig.cmake, so that smb::bullet's consumers
# find the same Bullet.
if(NOT TARGET SmbBullet::Collision)
  find_path(SMB_BULLET_INCLUDE_DIR btBulletCollisionCommon.h PATH_SUFFIXES bullet)
  find_library(SMB_BULLET_COLLISION_LIBRARY BulletCollision)
  find_library(SMB_BULLET_LINEAR_MATH_LIBRARY LinearMath)
  find_library(SMB_BULLET_DYNAMICS_LIBRARY BulletDynamics)
  if(SMB_BULLET_INCLUDE_DIR AND SMB_BULLET_COLLISION_LIBRARY AND SMB_BULLET_LINEAR_MATH_LIBRARY)
    add_library(SmbBullet::Collision INTERFACE IMPORTED)
    set_target_properties(SmbBullet::Collision PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${SMB_BULLET_INCLUDE_DIR}"
      INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${SMB_BULLET_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${SMB_BULLET_COLLISION_LIBRARY};${SMB_BULLET_LINEAR_MATH_LIBRARY}")
    if(SMB_BULLET_DYNAMICS_LIBRARY)
      add_library(SmbBullet::Dynamics INTERFACE IMPORTED)
      set_target_properties(SmbBullet::Dynamics PROPERTIES
        INTERFACE_LINK_LIBRARIES "${SMB_BULLET_DYNAMICS_LIBRARY};SmbBullet::Collision")
    endif()
  endif()
endif()
if(TARGET SmbBullet::Collision)
  set(SmbBullet_FOUND TRUE)
else()
  set(SmbBullet_FOUND FALSE)
endif()
