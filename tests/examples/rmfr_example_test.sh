#!/usr/bin/env bash
# The example application (examples/rmfr_deferred) as an outside program builds it:
# install foveal's SDK into a temporary prefix, build the example from a copy outside the
# source tree with find_package(foveal CONFIG), render headless at a live foveald's fovea
# (replay of the bundled log, --no-render), and check that its σ = 1 output equals its own
# full-resolution rendering (>= 40 dB) and that at σ_d 2 / σ_nd 3 the dominant eye is
# the sharper one, whichever eye that is.
# Usage: rmfr_example_test.sh BUILD_DIR SOURCE_DIR PYTHON3
set -euo pipefail
build=$1 src=$2 python=$3
test_name=rmfr_example_test
# shellcheck source=../support/prefix_test.sh
source "$src/tests/support/prefix_test.sh"

install_sdk
for f in include/foveal/rmfr.hpp include/foveal/rmfr_mapping.hpp include/foveal/core/error.hpp include/foveal/client.h; do
  [[ -f $prefix/$f ]] || fail "the prefix has no $f"
done
[[ -n $(find "$prefix" -path '*/foveal/rmfr/glsl/foveal/rmfr.glsl') ]] || fail "the prefix has no GLSL include files"
check_soname libfoveal-rmfr
# Only the library's own API is exported (foveal::image and core are linked in, hidden).
leaked=$(nm -D --defined-only -C "$so" | grep ' foveal::' | grep -v ' foveal::rmfr::' || true)
[[ -z $leaked ]] || { echo "$leaked" | head; fail "$so exports foveal symbols outside foveal::rmfr"; }

step "a C++ program with pkg-config --cflags --libs foveal-rmfr"
export PKG_CONFIG_PATH
PKG_CONFIG_PATH=$(dirname "$(find "$prefix" -name foveal-rmfr.pc)")
cat > "$work/plan.cpp" <<'CPP'
#include <foveal/rmfr.hpp>
#include <cstdio>
#include <string>
int main() {
  auto p = foveal::rmfr::plan_eye({.width = 1440, .height = 1600, .sigma = 2.0});
  if (!p) return std::fprintf(stderr, "%s\n", p.error().message.c_str()), 1;
  const std::string glsl = foveal::rmfr::glsl_directory();  // the prefix's, found from the library's place
  std::printf("  pkg-config: foveal-rmfr %s plans %dx%d, GLSL in %s\n", foveal::rmfr::version(), p->buffer_w, p->buffer_h, glsl.c_str());
  return p->buffer_w == 720 && p->buffer_h == 800 && glsl.rfind(PREFIX, 0) == 0 ? 0 : 1;
}
CPP
# shellcheck disable=SC2046
c++ -std=c++20 -Wall -Wextra -Werror -DPREFIX="\"$prefix\"" "$work/plan.cpp" -o "$work/plan" $(pkg-config --cflags --libs foveal-rmfr) \
  -Wl,-rpath,"$(pkg-config --variable=libdir foveal-rmfr)" || fail "the pkg-config program does not build"
"$work/plan" || fail "the pkg-config program failed"

step "the example from a copy outside the source tree, with find_package(foveal CONFIG)"
cp -r "$src/examples/rmfr_deferred" "$work/src"
cmake -S "$work/src" -B "$work/ex" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-Werror \
  > "$work/cmake.log" 2>&1 || { show "$work/cmake.log"; fail "the example does not configure"; }
cmake --build "$work/ex" > "$work/build.log" 2>&1 || { show "$work/build.log"; fail "the example does not build"; }
example=$work/ex/rmfr_deferred
libs=$(ldd "$example")
grep -q "$prefix.*libfoveal-rmfr" <<< "$libs" || { echo "$libs"; fail "the example does not load the prefix's libfoveal-rmfr"; }

start_foveald 600  # ended by the script; the duration is a hang guard

render() {  # NAME ARGS...: one frame set, its JSON line kept as NAME.json
  local name=$1
  shift
  "$example" --out "$work/$name.ppm" "$@" > "$work/$name.json" 2> "$work/$name.err" ||
    { show "$work/$name.json" "$work/$name.err" "$work/foveald.log"; fail "the example failed: $name"; }
  sed "s/^/  $name: /" "$work/$name.json"
}
render full --full
render sigma1 --live --sigma-d 1 --sigma-nd 1
render right --live --sigma-d 2 --sigma-nd 3 --dominant right
render left --live --sigma-d 2 --sigma-nd 3 --dominant left
render auto --live --sigma-d 2 --sigma-nd 3 --auto-f
"$build/bin/foveal" ctl set sigma_d=1.5 sigma_nd=2.5 > "$work/ctl.out" 2>&1 || { show "$work/ctl.out"; fail "foveal ctl set failed"; }
render settings --live

step "quality against the example's own full-resolution rendering"
"$python" - "$work" "$build/bin/foveal" <<'PY' || fail "quality checks failed"
import json, math, subprocess, sys
work, foveal = sys.argv[1], sys.argv[2]

def run(name):
    return json.load(open(f"{work}/{name}.json"))

def psnr(mse):
    return math.inf if mse == 0 else 10 * math.log10(255 ** 2 / mse)

def metrics(name):
    r = run(name)
    assert r["live"] and r["gaze_frame"] > 0, r
    for e in r["eyes"]:
        assert all(math.isfinite(v) and 0 <= v <= 1 for v in e["fovea"]), r
    (lx, ly), (rx, ry) = r["eyes"][0]["fovea"], r["eyes"][1]["fovea"]
    out = subprocess.run([foveal, "metrics", "--ref", f"{work}/full.ppm", "--test", f"{work}/{name}.ppm", "--stereo",
                          "--fovea", f"{lx},{ly}", "--fovea-right", f"{rx},{ry}", "--json"],
                         check=True, capture_output=True, text=True).stdout
    m = json.loads(out)
    return r, psnr(m["mse"]), psnr(m["left"]["mse"]), psnr(m["right"]["mse"])

r, combined, left, right = metrics("sigma1")
print(f"  sigma 1: PSNR {combined:.2f} dB (left {left:.2f}, right {right:.2f})")
assert [e["buffer"] for e in r["eyes"]] == [[480, 400], [480, 400]], r
assert combined >= 40, "the sigma-1 output is not the full-resolution rendering"
for dominant, name in ((1, "right"), (0, "left")):
    r, combined, left, right = metrics(name)
    print(f"  sigma_d 2 / sigma_nd 3, {name} dominant: left {left:.2f} dB, right {right:.2f} dB")
    assert r["dominant"] == dominant and r["eyes"][dominant]["buffer"] == [240, 200], r
    assert r["eyes"][1 - dominant]["buffer"] == [160, 133], r
    sharper, other = (right, left) if dominant == 1 else (left, right)
    assert sharper > other + 0.5, f"the dominant {name} eye is not the sharper one"
    assert other < 40, "sigma 3 should be visibly below the full rendering"
r = run("auto")
assert all(0.05 <= f <= 1.0 for f in r["f"]) and r["f"] != [0.3, 0.3], r  # estimate_f chose f
r, combined, left, right = metrics("auto")
print(f"  automatic f {r['f'][0]:.3f}, {r['f'][1]:.3f}: left {left:.2f} dB, right {right:.2f} dB")
r = run("settings")
d = r["dominant"]
assert r["eyes"][d]["sigma"] == 1.5 and r["eyes"][1 - d]["sigma"] == 2.5, r  # foveal ctl set reached the example
print(f"  foveal ctl set sigma_d=1.5 sigma_nd=2.5: the example renders {r['eyes'][d]['sigma']} / {r['eyes'][1 - d]['sigma']}")
PY
echo "rmfr_example_test: all passed"
