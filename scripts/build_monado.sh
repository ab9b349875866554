#!/usr/bin/env bash
# Builds Monado (the open-source OpenXR runtime, simulated HMD only) once from the vendored
# snapshot, into a cache outside the build tree, for foveal's OpenXR tests.
# Usage: scripts/build_monado.sh [--help]
# Env: FOVEAL_MONADO_TARBALL  the snapshot (default <repo>/../shared/vendor/monado/...)
#      FOVEAL_CACHE_DIR       the cache (default ${XDG_CACHE_HOME:-~/.cache}/foveal)
# Prints the runtime manifest's absolute path as the last line on stdout (logs: stderr).
# Without the snapshot a build cached before is used. Exit status 3: neither, so the
# OpenXR tests cannot run; anything else non-zero: failed.
set -euo pipefail

case "${1:-}" in
  -h | --help) sed -n '2,9s/^# \{0,1\}//p' "$0"; exit 0 ;;
  "") ;;
  *) echo "build_monado: unknown argument (try --help)" >&2; exit 2 ;;
esac

name=monado-8f85280
repo=$(cd "$(dirname "$0")/.." && pwd)
tarball=${FOVEAL_MONADO_TARBALL:-$repo/../shared/vendor/monado/$name.tar.xz}
cache=${FOVEAL_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/foveal}
final=$cache/$name
manifest=$final/build/openxr_monado-dev.json

# The library a manifest names, resolved as the loader does (relative: to the manifest).
library_of() {
  local lib
  lib=$(sed -n 's/.*"library_path": *"\([^"]*\)".*/\1/p' "$1")
  [[ $lib == /* ]] || lib=$(dirname "$1")/$lib
  printf '%s\n' "$lib"
}

if [[ ! -f $tarball ]]; then
  # A clone without the snapshot beside it still uses a build cached before (as CMake's
  # FovealTestOpenXRRuntime.cmake would), unchecked against a snapshot it cannot read.
  if [[ -f $manifest && -f $(library_of "$manifest") ]]; then
    echo "build_monado: no Monado snapshot at $tarball: using the build cached in $final" >&2
    printf '%s\n' "$manifest"
    exit 0
  fi
  echo "build_monado: no Monado snapshot at $tarball and no cached build in $final: the OpenXR tests cannot run" >&2
  exit 3
fi

# The flags of SOURCE.md beside the snapshot: no service (the runtime loads
# in-process), no optional media libraries, no driver but the simulated HMD.
flags=(-DCMAKE_BUILD_TYPE=Release -DXRT_FEATURE_SERVICE=OFF -DXRT_HAVE_OPENCV=OFF
  -DXRT_HAVE_SDL2=OFF -DXRT_HAVE_GST=OFF -DXRT_BUILD_DRIVER_SIMULATED=ON)
for d in ARDUINO DAYDREAM HDK HYDRA NS PSMV PSSENSE PSVR REMOTE RIFT RIFT_S ROKID SOLARXR \
  STEAMVR_LIGHTHOUSE TWRAP UVC VIVE WMR XREAL_AIR OHMD SURVIVE REALSENSE DEPTHAI ULV2 ULV5 \
  HANDTRACKING QWERTY ILLIXR EUROC SIMULAVR VF OPENGLOVES; do
  flags+=("-DXRT_BUILD_DRIVER_$d=OFF")
done
stamp="tarball_sha256=$(sha256sum <"$tarball" | cut -d' ' -f1) flags=${flags[*]}"

done_already() {
  [[ -f $final/stamp && $(<"$final/stamp") == "$stamp" && -f $manifest ]] &&
    [[ -f $(library_of "$manifest") ]]
}

mkdir -p "$cache"
exec 9>"$cache/$name.lock"
flock 9 # one build at a time: a second caller waits, then finds it done
if done_already; then
  printf '%s\n' "$manifest"
  exit 0
fi

rm -rf "$cache/$name".tmp.* # what killed builds left (we hold the lock)
tmp=$(mktemp -d "$cache/$name.tmp.XXXXXX")
chmod "$(umask -S)" "$tmp" # mktemp's 0700 would make the cache private
trap 'rm -rf "$tmp"' EXIT
echo "build_monado: building $name in $tmp (about a minute on 2 cores)" >&2
mkdir "$tmp/src"
# 9>&-: compilers orphaned by a kill must not keep holding the lock.
tar -xJf "$tarball" -C "$tmp/src" --strip-components=1 9>&-
# --no-warn-unused-cli: driver names this snapshot lacks (SOLARXR, UVC) are fine.
cmake -S "$tmp/src" -B "$tmp/build" -G Ninja --no-warn-unused-cli "${flags[@]}" >&2 9>&-
# Only the runtime library (and the manifest its link writes): about a third of the whole
# build, which adds Monado's tests, tools and imgui.
ninja -C "$tmp/build" openxr_monado >&2 9>&-

# The manifest names the library by its absolute path in $tmp, which the rename below
# would break: make it relative to the manifest (the loader allows that).
m=$tmp/build/openxr_monado-dev.json
json=$(<"$m")
printf '%s\n' "${json//"\"$tmp/build/"/\"./}" >"$m"
[[ -f $(library_of "$m") ]] || { echo "build_monado: $m names no built library" >&2; exit 1; }
printf '%s\n' "$stamp" >"$tmp/stamp"

# Swap in by renames, so a complete tree (with its stamp) is all $final ever holds.
[[ ! -e $final ]] || mv "$final" "$cache/$name.tmp.old"
mv "$tmp" "$final"
trap - EXIT
rm -rf "$cache/$name.tmp.old"
printf '%s\n' "$manifest"
