#!/usr/bin/env bash
# The SDK as an outside program meets it: install into a temporary prefix, build a C
# program with pkg-config and a CMake project with find_package(foveal CONFIG), run both
# and the installed Python module against a live foveald (replay of the bundled log,
# --no-render), change sigma_d under them with `foveal ctl set`, and put a marker into
# foveald's trace through the library.
# The C program is linked with `pkg-config --libs` alone and run without LD_LIBRARY_PATH:
# the .pc file of a non-system prefix carries the rpath (docs/sdk.md).
# Usage: install_test.sh BUILD_DIR SOURCE_DIR PYTHON3
set -euo pipefail
build=$1 src=$2 python=$3
test_name=install_test
# shellcheck source=../support/prefix_test.sh
source "$src/tests/support/prefix_test.sh"

install_sdk
for f in include/foveal/client.h; do [[ -f $prefix/$f ]] || fail "the prefix has no $f"; done
check_soname libfoveal-client
python_dir=$(dirname "$(find "$prefix" -path '*-packages/foveal/__init__.py')")
python_dir=$(dirname "$python_dir")
cp -r "$src/tests/sdk/consumers" "$work/src"  # the consumers build outside the source tree

step "a C program with pkg-config --cflags --libs foveal-client, and nothing else"
export PKG_CONFIG_PATH
PKG_CONFIG_PATH=$(dirname "$(find "$prefix" -name foveal-client.pc)")
# shellcheck disable=SC2046
cc -std=c11 -Wall -Wextra -Wpedantic -Werror "$work/src/consumer.c" -o "$work/consumer_c" \
  $(pkg-config --cflags --libs foveal-client) || fail "the C consumer does not build"
# From a non-system prefix it starts as built: the .pc file's rpath names the prefix's
# library, no LD_LIBRARY_PATH needed (the consumer runs below with none).
dynamic=$(readelf -d "$work/consumer_c")
grep -Eq "(RUNPATH|RPATH).*$prefix" <<< "$dynamic" || { echo "$dynamic"; fail "the C consumer has no rpath into $prefix"; }
resolved=$(env -u LD_LIBRARY_PATH ldd "$work/consumer_c")
grep -q "libfoveal-client.so.0 => $prefix" <<< "$resolved" || { echo "$resolved"; fail "libfoveal-client does not resolve into $prefix"; }

step "a system prefix (/usr, staged with DESTDIR) gets a .pc file without an rpath"
DESTDIR=$work/stage cmake --install "$build" --component sdk --prefix /usr > "$work/install-usr.log" \
  || { show "$work/install-usr.log"; fail "the DESTDIR install failed"; }
usr_pc=$(find "$work/stage/usr" -name foveal-client.pc)
[[ -n $usr_pc ]] || fail "the DESTDIR install has no foveal-client.pc"
# shellcheck disable=SC2016  # the .pc file's own ${libdir}, literally
grep -q '^Libs: -L${libdir} -lfoveal-client$' "$usr_pc" || { show "$usr_pc"; fail "$usr_pc: Libs is not plain -L/-l"; }

step "a CMake project with find_package(foveal CONFIG REQUIRED)"
cmake -S "$work/src/cmake" -B "$work/cmake-build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  > "$work/cmake.log" 2>&1 || { show "$work/cmake.log"; fail "the CMake consumer does not configure"; }
cmake --build "$work/cmake-build" > "$work/cmake-build.log" 2>&1 || { show "$work/cmake-build.log"; fail "the CMake consumer does not build"; }

start_foveald 600  # ended by the script; the duration is a hang guard

# NAME BINARY SIGMA_D: the consumer reads a fovea and says "ready"; then sigma_d changes.
run_consumer() {
  local name=$1 binary=$2 sigma=$3 pid
  env -u LD_LIBRARY_PATH "$binary" "$sigma" > "$work/$name.out" 2> "$work/$name.err" &
  pid=$!
  for _ in $(seq 600); do  # 60 s at least: a hang guard
    grep -q '^ready' "$work/$name.out" && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  grep -q '^ready' "$work/$name.out" || { show "$work/$name.out" "$work/$name.err" "$work/foveald.log"; fail "$name read no fovea"; }
  "$build/bin/foveal" ctl set "sigma_d=$sigma" > "$work/ctl.out" 2>&1 || { show "$work/ctl.out"; fail "foveal ctl set failed"; }
  wait "$pid" || { show "$work/$name.out" "$work/$name.err"; fail "$name did not see sigma_d=$sigma"; }
  sed "s/^/  $name: /" "$work/$name.out"
}
run_consumer c "$work/consumer_c" 2.5
run_consumer cmake "$work/cmake-build/consumer_cpp" 2.25

step "the installed Python module: live fovea, settings and a marker"
PYTHONPATH=$python_dir "$python" - "$prefix" <<'EOF' || fail "the installed Python module failed"
import math, sys, foveal
assert foveal.library_path().startswith(sys.argv[1]), foveal.library_path()  # the prefix's library, found by itself
with foveal.Client() as c:
    f = c.read()
    s = c.settings()
for e in (0, 1):
    assert math.isfinite(f.x[e]) and 0 <= f.x[e] <= f.eye_width and 0 <= f.y[e] <= f.eye_height, f
assert s.sigma_d == 2.25, s
print(f"  python: frame {f.frame} left ({f.x[0]:.1f}, {f.y[0]:.1f}) sigma_d {s.sigma_d} generation {s.generation}")
t_ns = foveal.mark("sdk: a marker from python")    # through libfoveal-client to the control socket
assert t_ns > 0, t_ns
for bad, code in (("two\nlines", foveal.INVALID_ARGUMENT), ("", foveal.INVALID_ARGUMENT)):
    try:
        foveal.mark(bad)
        sys.exit(f"mark({bad!r}) was taken")
    except foveal.ClientError as e:
        assert e.code == code, e
try:
    foveal.mark("nobody", socket=sys.argv[1] + "/no.sock")
    sys.exit("a mark to a missing socket was taken")
except foveal.ClientError as e:
    assert e.code == foveal.NO_WRITER and "no.sock" in str(e), e
print(f"  python: marker at {t_ns} ns")
EOF

step "foveald stops: clients are told"
kill -TERM "$foveald_pid"
wait "$foveald_pid" || fail "foveald exited with $?"
foveald_pid=""
PYTHONPATH=$python_dir "$python" - "$work/out/trace.csv" <<'EOF' || fail "the installed Python module failed"
import sys, foveal
try:
    foveal.Client()
    sys.exit("opened a block that foveald removed")
except foveal.ClientError as e:
    assert e.code == foveal.NO_WRITER, e
    print(f"  python: {e}")
t = foveal.read_trace(sys.argv[1])
assert len(t) > 10 and (t["t_ns"][1:] > t["t_ns"][:-1]).all(), len(t)
assert [m for m in t.markers if m[1] == "sdk: a marker from python"], t.markers
print(f"  python: trace {len(t)} samples, markers {t.markers}")
EOF
echo "install_test: all passed"
