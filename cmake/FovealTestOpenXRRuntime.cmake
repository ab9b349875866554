# The OpenXR runtime (Monado, built by scripts/build_monado.sh) and the core validation
# layer that the openxr tests use. include() it from the top-level CMakeLists.
#
# FOVEAL_TEST_OPENXR_RUNTIME (cache): the runtime manifest. When empty, the manifest in
#   build_monado.sh's default cache is used if it is there; the variable of that name in
#   the including scope holds the result either way (empty: tests reported as not run).
# FOVEAL_TEST_OPENXR_VALIDATION_LAYER_DIR (cache): the folder holding the core validation
#   layer's manifest, for XR_API_LAYER_PATH (NOTFOUND: none).

set(FOVEAL_TEST_OPENXR_RUNTIME "" CACHE FILEPATH
  "the OpenXR runtime manifest the openxr tests use; empty: those tests are reported as not run")

set(_foveal_xr_manifest "${FOVEAL_TEST_OPENXR_RUNTIME}")
if(_foveal_xr_manifest STREQUAL "")
  # The same default as scripts/build_monado.sh, so a plain configure finds a cached build.
  if(DEFINED ENV{FOVEAL_CACHE_DIR} AND NOT "$ENV{FOVEAL_CACHE_DIR}" STREQUAL "")
    set(_foveal_xr_cache "$ENV{FOVEAL_CACHE_DIR}")
  elseif(DEFINED ENV{XDG_CACHE_HOME} AND NOT "$ENV{XDG_CACHE_HOME}" STREQUAL "")
    set(_foveal_xr_cache "$ENV{XDG_CACHE_HOME}/foveal")
  else()
    set(_foveal_xr_cache "$ENV{HOME}/.cache/foveal")
  endif()
  set(_foveal_xr_manifest "${_foveal_xr_cache}/monado-8f85280/build/openxr_monado-dev.json")
endif()

# A manifest counts only if the library it names is there (relative: to the manifest).
set(_foveal_xr_library "")
if(EXISTS "${_foveal_xr_manifest}")
  file(READ "${_foveal_xr_manifest}" _foveal_xr_json)
  string(JSON _foveal_xr_library ERROR_VARIABLE _foveal_xr_err
    GET "${_foveal_xr_json}" runtime library_path)
  if(_foveal_xr_library AND NOT IS_ABSOLUTE "${_foveal_xr_library}")
    get_filename_component(_foveal_xr_dir "${_foveal_xr_manifest}" DIRECTORY)
    set(_foveal_xr_library "${_foveal_xr_dir}/${_foveal_xr_library}")
  endif()
endif()
if(_foveal_xr_library AND EXISTS "${_foveal_xr_library}")
  set(FOVEAL_TEST_OPENXR_RUNTIME "${_foveal_xr_manifest}")
else()
  if(NOT "${FOVEAL_TEST_OPENXR_RUNTIME}" STREQUAL "")
    message(WARNING "FOVEAL_TEST_OPENXR_RUNTIME=${FOVEAL_TEST_OPENXR_RUNTIME}: "
      "no such manifest, or the library it names is missing")
  endif()
  set(FOVEAL_TEST_OPENXR_RUNTIME "")
endif()

# Its manifest's name carries the multiarch triplet on Debian (...x86_64-linux-gnu.json).
if(NOT FOVEAL_TEST_OPENXR_VALIDATION_LAYER_DIR)
  set(_foveal_xr_dir FOVEAL_TEST_OPENXR_VALIDATION_LAYER_DIR-NOTFOUND)
  foreach(_foveal_xr_prefix /etc /usr/local/share /usr/share)
    file(GLOB _foveal_xr_layers
      "${_foveal_xr_prefix}/openxr/1/api_layers/explicit.d/XrApiLayer_core_validation*.json")
    if(_foveal_xr_layers)
      set(_foveal_xr_dir "${_foveal_xr_prefix}/openxr/1/api_layers/explicit.d")
      break()
    endif()
  endforeach()
  set(FOVEAL_TEST_OPENXR_VALIDATION_LAYER_DIR "${_foveal_xr_dir}" CACHE PATH
    "the folder of the OpenXR core validation layer's manifest, for XR_API_LAYER_PATH" FORCE)
endif()

if(FOVEAL_TEST_OPENXR_RUNTIME)
  set(_foveal_xr_msg "runtime ${FOVEAL_TEST_OPENXR_RUNTIME}")
else()
  set(_foveal_xr_msg "no runtime (run scripts/build_monado.sh): openxr tests reported as not run")
endif()
if(FOVEAL_TEST_OPENXR_VALIDATION_LAYER_DIR)
  string(APPEND _foveal_xr_msg "; validation layer in ${FOVEAL_TEST_OPENXR_VALIDATION_LAYER_DIR}")
else()
  string(APPEND _foveal_xr_msg "; no core validation layer (openxr-layer-corevalidation)")
endif()
message(STATUS "OpenXR tests: ${_foveal_xr_msg}")
unset(_foveal_xr_msg)
unset(_foveal_xr_manifest)
unset(_foveal_xr_library)
unset(_foveal_xr_json)
unset(_foveal_xr_err)
unset(_foveal_xr_dir)
unset(_foveal_xr_cache)
unset(_foveal_xr_prefix)
unset(_foveal_xr_layers)
