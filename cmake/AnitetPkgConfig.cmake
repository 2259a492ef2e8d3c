# anitet_pkg_config(NAME name INCLUDEDIR dir BUILD_LIBDIR dir BUILD_INCLUDEDIR dir)
# Writes two pkg-config files from ${CMAKE_CURRENT_SOURCE_DIR}/<name>.pc.in, whose @PC_PREFIX@,
# @PC_LIBDIR@, @PC_INCLUDEDIR@ and @PC_RPATH@ it sets:
# - the installed <libdir>/pkgconfig/<name>.pc (component capi), with INCLUDEDIR (relative to the
#   prefix, or absolute) as includedir and the prefix given to `cmake --install` (written then,
#   so that --prefix DIR gives a file naming DIR; `pkg-config --define-prefix` if the tree moves).
# - <build>/pkgconfig/<name>-uninstalled.pc, for the build tree (BUILD_LIBDIR may be a generator
#   expression): pkg-config prefers it when PKG_CONFIG_PATH holds <build>/pkgconfig.
# With ANITET_PKGCONFIG_RPATH, Libs also says -Wl,-rpath,${libdir}, so that a program linked
# with `pkg-config --libs` finds the library at run time without LD_LIBRARY_PATH.
include(GNUInstallDirs)

function(anitet_pkg_config)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "NAME;INCLUDEDIR;BUILD_LIBDIR;BUILD_INCLUDEDIR" "")
  set(template ${CMAKE_CURRENT_SOURCE_DIR}/${arg_NAME}.pc.in)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${template})
  set(PC_RPATH "")
  if(ANITET_PKGCONFIG_RPATH)
    set(PC_RPATH "-Wl,-rpath,\${libdir} ")
  endif()

  # Installed: the prefix is written when installing (`cmake --install build --prefix DIR`).
  set(PC_PREFIX "@PC_INSTALL_PREFIX@")
  set(PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
  set(destination "\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/pkgconfig")
  if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
    set(PC_LIBDIR "${CMAKE_INSTALL_LIBDIR}")
    set(destination "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
  endif()
  set(PC_INCLUDEDIR "\${prefix}/${arg_INCLUDEDIR}")
  if(IS_ABSOLUTE "${arg_INCLUDEDIR}")
    set(PC_INCLUDEDIR "${arg_INCLUDEDIR}")
  endif()
  set(staged ${CMAKE_CURRENT_BINARY_DIR}/for-install)
  configure_file(${template} ${staged}/${arg_NAME}.pc.in @ONLY)
  install(CODE "
    file(READ \"${staged}/${arg_NAME}.pc.in\" text)
    string(REPLACE \"@PC_INSTALL_PREFIX@\" \"\${CMAKE_INSTALL_PREFIX}\" text \"\${text}\")
    file(WRITE \"${staged}/${arg_NAME}.pc\" \"\${text}\")
    file(INSTALL \"${staged}/${arg_NAME}.pc\" DESTINATION \"${destination}\")
  " COMPONENT capi)

  # The build tree.
  set(PC_PREFIX "${PROJECT_BINARY_DIR}")
  set(PC_LIBDIR "${arg_BUILD_LIBDIR}")
  set(PC_INCLUDEDIR "${arg_BUILD_INCLUDEDIR}")
  configure_file(${template} ${CMAKE_CURRENT_BINARY_DIR}/${arg_NAME}-uninstalled.pc.in @ONLY)
  file(GENERATE OUTPUT ${PROJECT_BINARY_DIR}/pkgconfig/${arg_NAME}-uninstalled.pc
       INPUT ${CMAKE_CURRENT_BINARY_DIR}/${arg_NAME}-uninstalled.pc.in)
endfunction()
