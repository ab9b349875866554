# The SDK: shared libraries for other programs, installed with their headers, a
# pkg-config file each and the CMake package `foveal` (docs/sdk.md).
#
# foveal_sdk_library(NAME COMPONENT C SOURCES ... [HEADERS DIR...] [PUBLIC_DEPS ...]
#   [PRIVATE_DEPS ...] [FIND_DEPENDENCIES PKG...] [DESCRIPTION TEXT] [PC_REQUIRES ...]
#   [PC_LIBS_PRIVATE ...])
# makes libfoveal-C.so (SONAME libfoveal-C.so.<major>, version <project version>), its
# alias and exported target foveal::C, installs it with the headers under each HEADERS
# folder (relative to this directory; default include), foveal-C.pc and the package's
# component file foveal-C-component.cmake: find_package(foveal CONFIG) finds every
# component installed beside it, so a new library only calls this function.
# PRIVATE_DEPS are linked into the library only (foveal's static libraries: they and the
# static libraries they link are switched to -fPIC); FIND_DEPENDENCIES are packages the
# exported target needs (find_dependency).
include(CMakePackageConfigHelpers)
set(FOVEAL_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/foveal)
set(FOVEAL_SDK_TEMPLATES ${CMAKE_CURRENT_LIST_DIR}/sdk)

# A static library linked into a shared one must be position-independent, and so must
# every static library it links in turn.
function(_foveal_sdk_make_pic dep)
  if(NOT TARGET ${dep})
    return()
  endif()
  get_target_property(real ${dep} ALIASED_TARGET)
  if(real)
    set(dep ${real})
  endif()
  get_target_property(type ${dep} TYPE)
  get_target_property(imported ${dep} IMPORTED)
  if(imported OR NOT type STREQUAL "STATIC_LIBRARY")
    return()
  endif()
  get_target_property(done ${dep} POSITION_INDEPENDENT_CODE)
  if(done)
    return()
  endif()
  set_target_properties(${dep} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  get_target_property(links ${dep} LINK_LIBRARIES)
  foreach(link IN LISTS links)
    if(NOT link MATCHES "^\\$<")
      _foveal_sdk_make_pic(${link})
    endif()
  endforeach()
endfunction()

function(foveal_sdk_library name)
  cmake_parse_arguments(ARG "" "COMPONENT;DESCRIPTION"
    "SOURCES;HEADERS;PUBLIC_DEPS;PRIVATE_DEPS;FIND_DEPENDENCIES;PC_REQUIRES;PC_LIBS_PRIVATE" ${ARGN})
  if(NOT ARG_COMPONENT)
    message(FATAL_ERROR "foveal_sdk_library(${name}): COMPONENT is required")
  endif()
  if(NOT ARG_HEADERS)
    set(ARG_HEADERS include)
  endif()
  set(c ${ARG_COMPONENT})
  add_library(${name} SHARED ${ARG_SOURCES})
  add_library(foveal::${c} ALIAS ${name})
  set_target_properties(${name} PROPERTIES
    OUTPUT_NAME foveal-${c} EXPORT_NAME ${c}
    VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}
    C_VISIBILITY_PRESET hidden CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON
    LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/lib)
  foreach(dir IN LISTS ARG_HEADERS)
    target_include_directories(${name} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/${dir}>)
    install(DIRECTORY ${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT sdk)
  endforeach()
  target_include_directories(${name} INTERFACE $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_DEPS})
  foreach(dep IN LISTS ARG_PRIVATE_DEPS)
    target_link_libraries(${name} PRIVATE $<BUILD_INTERFACE:${dep}>)  # linked in; not part of the export
    _foveal_sdk_make_pic(${dep})
  endforeach()
  foveal_target_defaults(${name})

  install(TARGETS ${name} EXPORT foveal-${c}-targets
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT sdk)
  install(EXPORT foveal-${c}-targets NAMESPACE foveal:: FILE foveal-${c}-targets.cmake
    DESTINATION ${FOVEAL_INSTALL_CMAKEDIR} COMPONENT sdk)

  # The package's component file: its dependencies, then its targets.
  set(FOVEAL_COMPONENT ${c})
  set(FOVEAL_FIND_DEPENDENCIES "")
  foreach(dep IN LISTS ARG_FIND_DEPENDENCIES)
    string(APPEND FOVEAL_FIND_DEPENDENCIES "find_dependency(${dep})\n")
  endforeach()
  configure_file(${FOVEAL_SDK_TEMPLATES}/foveal-component.cmake.in
    ${CMAKE_BINARY_DIR}/sdk/foveal-${c}-component.cmake @ONLY)
  install(FILES ${CMAKE_BINARY_DIR}/sdk/foveal-${c}-component.cmake
    DESTINATION ${FOVEAL_INSTALL_CMAKEDIR} COMPONENT sdk)

  # pkg-config, relocatable: the prefix is found from the .pc file's own place.
  file(RELATIVE_PATH FOVEAL_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
  string(REGEX REPLACE "/$" "" FOVEAL_PC_TO_PREFIX "${FOVEAL_PC_TO_PREFIX}")
  set(FOVEAL_PC_DESCRIPTION "${ARG_DESCRIPTION}")
  list(JOIN ARG_PC_REQUIRES ", " FOVEAL_PC_REQUIRES)
  list(JOIN ARG_PC_LIBS_PRIVATE " " FOVEAL_PC_LIBS_PRIVATE)
  # Two forms; the install takes one by where the library lands (its prefix is known only
  # then: `cmake --install --prefix`). Outside the directories the linker and the loader
  # search anyway, Libs carries -Wl,-rpath,${libdir}, so that a program built with
  # `pkg-config --libs` starts without LD_LIBRARY_PATH; in them (/usr: Debian policy) it
  # carries none (docs/sdk.md).
  set(FOVEAL_PC_RPATH "")
  configure_file(${FOVEAL_SDK_TEMPLATES}/foveal-component.pc.in ${CMAKE_BINARY_DIR}/sdk/foveal-${c}.pc @ONLY)
  set(FOVEAL_PC_RPATH " -Wl,-rpath,\${libdir}")
  configure_file(${FOVEAL_SDK_TEMPLATES}/foveal-component.pc.in ${CMAKE_BINARY_DIR}/sdk/rpath/foveal-${c}.pc @ONLY)
  set(system_dirs ${CMAKE_PLATFORM_IMPLICIT_LINK_DIRECTORIES} ${CMAKE_C_IMPLICIT_LINK_DIRECTORIES}
    ${CMAKE_CXX_IMPLICIT_LINK_DIRECTORIES})
  install(CODE "set(FOVEAL_PC_PLAIN \"${CMAKE_BINARY_DIR}/sdk/foveal-${c}.pc\")
set(FOVEAL_PC_WITH_RPATH \"${CMAKE_BINARY_DIR}/sdk/rpath/foveal-${c}.pc\")
set(FOVEAL_PC_LIBDIR \"${CMAKE_INSTALL_LIBDIR}\")
set(FOVEAL_SYSTEM_LIBDIRS \"${system_dirs}\")
include(\"${FOVEAL_SDK_TEMPLATES}/install-pc.cmake\")" COMPONENT sdk)
endfunction()

# The package's entry files; called once, from the top-level CMakeLists.
function(foveal_sdk_package)
  configure_package_config_file(${FOVEAL_SDK_TEMPLATES}/fovealConfig.cmake.in
    ${CMAKE_BINARY_DIR}/sdk/fovealConfig.cmake INSTALL_DESTINATION ${FOVEAL_INSTALL_CMAKEDIR})
  write_basic_package_version_file(${CMAKE_BINARY_DIR}/sdk/fovealConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
  install(FILES ${CMAKE_BINARY_DIR}/sdk/fovealConfig.cmake ${CMAKE_BINARY_DIR}/sdk/fovealConfigVersion.cmake
    DESTINATION ${FOVEAL_INSTALL_CMAKEDIR} COMPONENT sdk)
endfunction()
