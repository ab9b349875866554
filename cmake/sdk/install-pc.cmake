# Install-time half of foveal_sdk_library's pkg-config file (cmake/FovealSdk.cmake): puts
# FOVEAL_PC_WITH_RPATH under <prefix>/FOVEAL_PC_LIBDIR/pkgconfig when the library's
# folder is none the linker and the loader search by themselves (FOVEAL_SYSTEM_LIBDIRS,
# the compilers' implicit link directories), else FOVEAL_PC_PLAIN. Runs inside
# cmake_install.cmake, where CMAKE_INSTALL_PREFIX is the prefix installed to.
if(IS_ABSOLUTE "${FOVEAL_PC_LIBDIR}")
  set(_foveal_libdir "${FOVEAL_PC_LIBDIR}")
else()
  set(_foveal_libdir "${CMAKE_INSTALL_PREFIX}/${FOVEAL_PC_LIBDIR}")
endif()
cmake_path(NORMAL_PATH _foveal_libdir)
string(REGEX REPLACE "(.)/$" "\\1" _foveal_libdir "${_foveal_libdir}")
set(_foveal_pc "${FOVEAL_PC_WITH_RPATH}")
foreach(_foveal_dir IN LISTS FOVEAL_SYSTEM_LIBDIRS)
  cmake_path(NORMAL_PATH _foveal_dir)
  string(REGEX REPLACE "(.)/$" "\\1" _foveal_dir "${_foveal_dir}")
  if(_foveal_dir STREQUAL _foveal_libdir)
    set(_foveal_pc "${FOVEAL_PC_PLAIN}")
  endif()
endforeach()
get_filename_component(_foveal_pc_name "${FOVEAL_PC_PLAIN}" NAME)
file(INSTALL DESTINATION "${_foveal_libdir}/pkgconfig" TYPE FILE RENAME "${_foveal_pc_name}" FILES "${_foveal_pc}")
