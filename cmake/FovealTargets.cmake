# Common settings for every foveal target: warnings and sanitizers.
function(foveal_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
    -Wno-sign-conversion)
endfunction()

# foveal_library(NAME ALIAS SOURCES... [DEPS ...])
function(foveal_library name)
  # INCLUDES: public header folders relative to this directory (default: include).
  cmake_parse_arguments(ARG "" "ALIAS" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS;INCLUDES" ${ARGN})
  if(NOT ARG_INCLUDES)
    set(ARG_INCLUDES include)
  endif()
  list(TRANSFORM ARG_INCLUDES PREPEND ${CMAKE_CURRENT_SOURCE_DIR}/)
  add_library(${name} STATIC ${ARG_SOURCES})
  add_library(${ARG_ALIAS} ALIAS ${name})
  target_include_directories(${name} PUBLIC ${ARG_INCLUDES})
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  foveal_target_defaults(${name})
endfunction()

function(foveal_executable name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS})
  foveal_target_defaults(${name})
endfunction()
