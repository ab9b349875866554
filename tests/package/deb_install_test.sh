#!/usr/bin/env bash
# The Debian package as a new machine meets it: build it (scripts/package.sh, lintian
# included), make a fresh Debian 12 root with mmdebstrap from Debian's mirror, install the
# package there with apt (dependencies from the mirror), and check inside the root: the
# programs print the project's version, the Khronos loader lists the layer and `foveal
# openxr` finds its manifest, the udev rules, the user unit, the libraries in ld.so's
# cache, the Python module, foveald on the bundled recording; then purge it and check that
# nothing is left. The root is made and removed by the test.
# Usage: deb_install_test.sh SOURCE_DIR PKG_BUILD_DIR VERSION
#   FOVEAL_DEB=FILE: test this .deb instead of building one
#   FOVEAL_DEBIAN_MIRROR (default http://deb.debian.org/debian), FOVEAL_DEBIAN_SECURITY
#   (default http://deb.debian.org/debian-security): where the root's packages come from.
# Needs root (mmdebstrap's root mode, chroot), mmdebstrap, lintian and the mirror.
set -euo pipefail
src=$1 pkg_build=$2 version=$3
started=$(date +%s)
fail() { echo "deb_install_test: FAIL: $*" >&2; exit 1; }
step() { printf '== %s (%d s)\n' "$*" $(($(date +%s) - started)); }
show() { for f in "$@"; do echo "--- $f"; tail -40 "$f"; done; }
[[ $(id -u) -eq 0 ]] || fail "needs root (mmdebstrap makes the root as root, and the checks chroot into it)"
command -v mmdebstrap > /dev/null || fail "mmdebstrap is not installed (apt-get install mmdebstrap lintian)"

work=$(mktemp -d "${TMPDIR:-/tmp}/foveal-deb-test.XXXXXX")
root=$work/root
cleanup() {
  if mountpoint -q "$root/proc" && ! umount "$root/proc"; then
    echo "deb_install_test: $root/proc is still mounted: $work is left in place" >&2
    return
  fi
  rm -rf --one-file-system "$work"
}
trap cleanup EXIT

deb=${FOVEAL_DEB:-}
if [[ -z $deb ]]; then
  step "scripts/package.sh --build-dir $pkg_build"
  "$src/scripts/package.sh" --build-dir "$pkg_build" --out "$work/out" | tee "$work/package.log" ||
    fail "scripts/package.sh failed (above)"
  deb=$(tail -1 "$work/package.log")
fi
[[ -f $deb ]] || fail "no package at '$deb'"
deb=$(realpath "$deb")
[[ $(dpkg-deb -f "$deb" Version) == "$version"-* ]] ||
  fail "$deb is version $(dpkg-deb -f "$deb" Version), the project is at $version"

mirror=${FOVEAL_DEBIAN_MIRROR:-http://deb.debian.org/debian}
security=${FOVEAL_DEBIAN_SECURITY:-http://deb.debian.org/debian-security}
step "mmdebstrap: a Debian 12 root with $(basename "$deb") and its dependencies from $mirror"
# The hook makes the local .deb visible to dpkg inside the root (mmdebstrap(1), --include).
mmdebstrap --variant=apt --hook-dir=/usr/share/mmdebstrap/hooks/file-mirror-automount --include="$deb" \
  bookworm "$root" "deb $mirror bookworm main" \
  "deb $mirror bookworm-updates main" "deb $security bookworm-security main" > "$work/mmdebstrap.log" 2>&1 ||
  { show "$work/mmdebstrap.log"; fail "mmdebstrap could not make the root or install the package into it (log above; is $mirror reachable?)"; }
mount -t proc proc "$root/proc" || fail "cannot mount /proc in $root"
in_root() { chroot "$root" env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin "$@"; }

step "installed: dpkg, --version"
# shellcheck disable=SC2016  # dpkg-query's own ${Status}, literally
status=$(in_root dpkg-query -W -f='${Status} ${Version}' foveal) || fail "dpkg does not know foveal in the root"
[[ $status == "install ok installed $version-"* ]] || fail "foveal in the root: '$status'"
for p in foveald foveal; do
  got=$(in_root "$p" --version 2>&1) || fail "$p --version in the root exited $?: $got"
  [[ $got == "$p $version" ]] || fail "$p --version in the root prints '$got', expected '$p $version'"
  echo "  $p --version: $got"
done

step "udev rules, user unit, libraries, headers, pkg-config and CMake files"
rules=""
for d in usr/lib/udev/rules.d lib/udev/rules.d; do [[ -f $root/$d/70-foveal.rules ]] && rules=/$d/70-foveal.rules && break; done
[[ -n $rules ]] || fail "the root has no 70-foveal.rules in /usr/lib/udev/rules.d or /lib/udev/rules.d"
grep -q 'TAG+="uaccess"' "$root$rules" || fail "$rules has no uaccess rule"
unit=$root/usr/lib/systemd/user/foveald.service
[[ -f $unit ]] || fail "the root has no user unit /usr/lib/systemd/user/foveald.service"
grep -qx 'ExecStart=/usr/bin/foveald --service --quiet' "$unit" ||
  fail "$unit does not start /usr/bin/foveald --service: $(grep ExecStart "$unit")"
cache=$(in_root ldconfig -p) || fail "ldconfig -p failed in the root"
for lib in libfoveal-client.so.0 libfoveal-rmfr.so.0; do
  grep -q "$lib " <<< "$cache" || fail "$lib is not in the root's ld.so cache (the ldconfig trigger)"
done
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || echo x86_64-linux-gnu)
for f in usr/include/foveal/client.h usr/lib/$multiarch/pkgconfig/foveal-client.pc \
         usr/lib/$multiarch/cmake/foveal/fovealConfig.cmake usr/share/foveal/data/gaze/vive_pro_eye_TESTNA01.csv \
         usr/share/doc/foveal/copyright usr/share/doc/foveal/daemon.md; do
  [[ -f $root/$f ]] || fail "the root has no /$f"
done
# shellcheck disable=SC2016  # the .pc file's own ${libdir}, literally
grep -q '^Libs: -L${libdir} -lfoveal-client$' "$root/usr/lib/$multiarch/pkgconfig/foveal-client.pc" ||
  fail "foveal-client.pc (prefix /usr) is not plain -L/-l: $(grep '^Libs' "$root/usr/lib/$multiarch/pkgconfig/foveal-client.pc")"

step "OpenXR: the loader lists the layer, foveal openxr finds it"
layers=$(in_root python3 - <<'EOF'
# xrEnumerateApiLayerProperties from the root's own loader (libopenxr-loader1).
import ctypes
class Props(ctypes.Structure):
    _fields_ = [("type", ctypes.c_int), ("next", ctypes.c_void_p), ("layerName", ctypes.c_char * 256),
                ("specVersion", ctypes.c_uint64), ("layerVersion", ctypes.c_uint32), ("description", ctypes.c_char * 256)]
xr = ctypes.CDLL("libopenxr_loader.so.1")
n = ctypes.c_uint32(0)
assert xr.xrEnumerateApiLayerProperties(0, ctypes.byref(n), None) == 0, "the count call failed"
props = (Props * n.value)()
for p in props:
    p.type = 1  # XR_TYPE_API_LAYER_PROPERTIES
assert xr.xrEnumerateApiLayerProperties(n.value, ctypes.byref(n), props) == 0, "the list call failed"
for p in props:
    print(p.layerName.decode())
EOF
) || fail "the root's OpenXR loader could not list its API layers"
grep -qx XR_APILAYER_FOVEAL_gaze <<< "$layers" || fail "the root's OpenXR loader does not list XR_APILAYER_FOVEAL_gaze (it lists: ${layers:-nothing})"
echo "  the loader lists: $(paste -sd' ' <<< "$layers")"
in_root foveal openxr --json > "$work/openxr.json" 2> "$work/openxr.err" || true  # no runtime in the root: exit 1
layer_lib=$(python3 - "$work/openxr.json" <<'EOF'
import json, sys
layer = json.load(open(sys.argv[1]))["layer"]
found = [m for m in layer["manifests"] if m["kind"] == "implicit"
         and m["manifest"] == "/usr/share/openxr/1/api_layers/implicit.d/XrApiLayer_foveal_gaze.json"]
assert found, f"no implicit manifest under /usr/share/openxr/1/api_layers: {layer['manifests']}"
assert found[0]["library_exists"] and not found[0]["problem"], found[0]
assert layer["enabled"], layer["why"]
print(found[0]["library"])
EOF
) || { show "$work/openxr.json" "$work/openxr.err"; fail "foveal openxr in the root does not find the installed layer (above)"; }
echo "  foveal openxr: implicit.d/XrApiLayer_foveal_gaze.json -> $layer_lib"
in_root python3 -c 'import ctypes, sys; ctypes.CDLL(sys.argv[1])' "$layer_lib" ||
  fail "the layer's library $layer_lib does not load in the root (a library it needs is missing?)"

step "the Python module, foveald on the bundled recording"
got=$(in_root python3 -c 'import foveal; print(foveal.__version__, foveal.library_path())') ||
  fail "the Python module does not import or load libfoveal-client in the root"
[[ $got == "$version /usr/lib/$multiarch/libfoveal-client.so.0" ]] || fail "the Python module says '$got'"
echo "  python3 -c 'import foveal': $got"
# The gaze side only (the root has no EGL driver: Mesa is a Recommends), as fast as it goes.
in_root foveald --no-render --no-control --no-shm --speed 0 --quiet --out /tmp/foveald-out > "$work/foveald.log" 2>&1 ||
  { show "$work/foveald.log"; fail "foveald on the bundled recording failed in the root"; }
[[ -s $root/tmp/foveald-out/trace.csv ]] || { show "$work/foveald.log"; fail "foveald wrote no trace.csv in the root"; }
echo "  foveald --no-render: $(($(wc -l < "$root/tmp/foveald-out/trace.csv") - 1)) trace rows from /usr/share/foveal/data"

step "apt-get purge foveal: nothing of it left"
in_root apt-get purge -y -q foveal > "$work/purge.log" 2>&1 || { show "$work/purge.log"; fail "apt-get purge foveal failed"; }
left=$(cd "$root" || exit; find usr/bin/foveal usr/bin/foveald usr/lib/python3/dist-packages/foveal usr/share/foveal \
  usr/share/openxr/1/api_layers/implicit.d/XrApiLayer_foveal_gaze.json "${rules#/}" 2>/dev/null || true)
[[ -z $left ]] || fail "the purge left: $left"
grep -qi "warning" "$work/purge.log" && { show "$work/purge.log"; fail "the purge warned (above)"; }
step "passed"
