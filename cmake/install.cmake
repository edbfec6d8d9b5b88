# Installation: headers, libraries, the cyclone-world runner and cyclone-viewer, a CMake package
# (find_package(cyclone CONFIG): cyclone::core, cyclone::world) and a pkg-config file.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(cyclone_install_targets cyclone_core)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/cyclone DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(CYCLONE_BUILD_WORLD)
  list(APPEND cyclone_install_targets cyclone_world)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/world/include/cyclone DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()

install(TARGETS ${cyclone_install_targets} EXPORT cycloneTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The tools, when built: the scene runner and the viewer.
foreach(tool cyclone-world cyclone-viewer)
  if(TARGET ${tool})
    install(TARGETS ${tool} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endforeach()

set(cyclone_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/cyclone)
install(EXPORT cycloneTargets NAMESPACE cyclone:: DESTINATION ${cyclone_cmake_dir})

if(BUILD_SHARED_LIBS)
  set(BUILD_SHARED_LIBS_VALUE ON)
else()
  set(BUILD_SHARED_LIBS_VALUE OFF)
endif()
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/cycloneConfig.cmake.in
  ${PROJECT_BINARY_DIR}/cycloneConfig.cmake
  INSTALL_DESTINATION ${cyclone_cmake_dir})
# 0.x: a minor version may break the API, so only the same major.minor is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cycloneConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cycloneConfig.cmake ${PROJECT_BINARY_DIR}/cycloneConfigVersion.cmake
  DESTINATION ${cyclone_cmake_dir})

# pkg-config: static libraries need their dependencies on every link line; FCL's own
# .pc file adds -std=c++11, so it is named by library rather than required.
if(CYCLONE_BUILD_WORLD)
  set(cyclone_pc_world "-lcyclone_world")
  set(cyclone_pc_deps "-lfcl -lccd -lqhull_r -pthread -lm")
else()
  set(cyclone_pc_world "")
  set(cyclone_pc_deps "")
endif()
if(BUILD_SHARED_LIBS)
  set(CYCLONE_PC_LIBS "${cyclone_pc_world} -lcyclone_core")
  set(CYCLONE_PC_LIBS_PRIVATE "${cyclone_pc_deps}")
else()
  string(STRIP "${cyclone_pc_world} -lcyclone_core ${cyclone_pc_deps}" CYCLONE_PC_LIBS)
  set(CYCLONE_PC_LIBS_PRIVATE "")
endif()
# Relocatable: the prefix is found from the .pc file's own place (cmake --install --prefix).
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(CYCLONE_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
  set(CYCLONE_PC_LIBDIR "${CMAKE_INSTALL_LIBDIR}")
else()
  file(RELATIVE_PATH cyclone_pc_up "/root/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/root")
  set(CYCLONE_PC_PREFIX "\${pcfiledir}/${cyclone_pc_up}")
  set(CYCLONE_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
endif()
if(IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  set(CYCLONE_PC_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}")
else()
  set(CYCLONE_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
endif()
configure_file(${CMAKE_CURRENT_LIST_DIR}/cyclone.pc.in ${PROJECT_BINARY_DIR}/cyclone.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/cyclone.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
