# Shared by the shell tests that meet foveal as an outside program does (tests/sdk,
# tests/examples): a scratch directory removed on exit, messages, the SDK installed into a
# temporary prefix, and a live foveald replaying the bundled log without rendering.
# Source it after setting `test_name`, `build` and `src`.
work=$(mktemp -d "${TMPDIR:-/tmp}/foveal-$test_name-XXXXXX")
foveald_pid=""
cleanup() {
  if [[ -n $foveald_pid ]]; then kill "$foveald_pid" 2>/dev/null || true; wait "$foveald_pid" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "$test_name: $*" >&2; exit 1; }
show() { for f in "$@"; do [[ -s $f ]] && { echo "--- $f"; cat "$f"; }; done; return 0; }
step() { echo "== $*"; }

# cmake --install --component sdk into $work/prefix; sets `prefix`.
install_sdk() {
  step "cmake --install --component sdk into a temporary prefix"
  prefix=$work/prefix
  cmake --install "$build" --component sdk --prefix "$prefix" > "$work/install.log" || { show "$work/install.log"; fail "install failed"; }
}

# A versioned shared library LIB (e.g. libfoveal-client) in the prefix, with its SONAME;
# sets `so`. (readelf's output is captured first: with pipefail, `readelf | grep -q`
# fails when grep stops reading early.)
check_soname() {
  local lib=$1 dynamic
  so=$(find "$prefix" -name "$lib.so.*.*.*" | head -1)
  [[ -n $so ]] || fail "the prefix has no versioned $lib.so"
  dynamic=$(readelf -d "$so")
  grep -q "SONAME.*${lib//./\\.}\\.so\\.[0-9]" <<< "$dynamic" || fail "$so has no SONAME"
}

# foveald on the bundled recording for at most SECONDS, with its own shared block, control
# socket and configuration under $work; sets `foveald_pid`.
start_foveald() {
  local seconds=$1
  step "a live foveald (replay, --no-render) with its own block and control socket"
  export FOVEAL_SHM_NAME=/foveal-$test_name-$$
  export XDG_RUNTIME_DIR=$work/run XDG_CONFIG_HOME=$work/config
  mkdir -p "$XDG_RUNTIME_DIR" "$XDG_CONFIG_HOME"
  "$build/bin/foveald" --replay "$src/data/gaze/vive_pro_eye_TESTNA01.csv" --no-render --loop --end 12 --duration "$seconds" -q \
    --out "$work/out" > "$work/foveald.log" 2>&1 &
  foveald_pid=$!
}
