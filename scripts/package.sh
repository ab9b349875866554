#!/usr/bin/env bash
# Builds the Debian package `foveal` from this tree: configures and builds a Release tree
# for the prefix /usr without tests, installs it (stripped) into a staging folder, and
# makes OUT/foveal_<version>-<rev>_<arch>.deb with dpkg-shlibdeps, dpkg-gencontrol and
# dpkg-deb, then checks it with lintian (when installed). docs/install.md, "Package".
# Usage: scripts/package.sh [--build-dir DIR] [--out DIR] [--jobs N] [--no-lintian]
#   --build-dir DIR  the package's build tree (default: build-pkg)
#   --out DIR        where the .deb goes (default: out); its path is the last line printed
#   --jobs N         parallel compile jobs (default: nproc)
#   --no-lintian     skip lintian (by default an error from lintian fails the script)
# Needs what scripts/bootstrap.sh installs (dpkg-dev included), and lintian for the check.
set -euo pipefail
cd "$(dirname "$0")/.."
src=$PWD
build=build-pkg out=out jobs=$(nproc) lintian=1
die() { echo "package.sh: $*" >&2; exit 2; }
while (($#)); do
  case "$1" in
    --build-dir) [[ $# -ge 2 ]] || die "--build-dir needs a folder"; build=$2; shift 2 ;;
    --out) [[ $# -ge 2 ]] || die "--out needs a folder"; out=$2; shift 2 ;;
    --jobs) [[ ${2:-} =~ ^[1-9][0-9]*$ ]] || die "--jobs needs a positive number"; jobs=$2; shift 2 ;;
    --no-lintian) lintian=0; shift ;;
    -h|--help) sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown argument '$1' (scripts/package.sh --help)" ;;
  esac
done
for tool in cmake ninja dpkg-deb dpkg-shlibdeps dpkg-gencontrol dpkg-parsechangelog; do
  command -v "$tool" > /dev/null || die "$tool is not installed (Debian: apt-get install dpkg-dev cmake ninja-build)"
done
((lintian == 0)) || command -v lintian > /dev/null ||
  die "lintian is not installed (apt-get install lintian), or pass --no-lintian"
umask 022
mkdir -p "$out"
build=$(realpath "$build") out=$(realpath "$out")
step() { printf '== %s\n' "$*"; }

# The package's own flags: Debian's (dpkg-buildflags: -O2 and hardening) without -g, as
# the binaries ship stripped; the prefix /usr is compiled in (the data folder).
hardening="-fstack-protector-strong -Wformat -Werror=format-security -D_FORTIFY_SOURCE=2"
release="-O2 -DNDEBUG"
link="-Wl,-z,relro -Wl,-z,now"
launcher=()
# shellcheck source=SCRIPTDIR/compiler_cache.sh
source scripts/compiler_cache.sh
step "configure $build (Release, prefix /usr, no tests)"
mkdir -p "$build"
# FOVEAL_INSTALL_PYTHONDIR as STRING: cmake would make a relative PATH value absolute (against $PWD).
cmake -S "$src" -B "$build" -G Ninja "${launcher[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DFOVEAL_BUILD_TESTS=OFF -DFOVEAL_BUILD_BENCHMARKS=OFF -DCMAKE_INSTALL_PREFIX=/usr \
  -DFOVEAL_INSTALL_PYTHONDIR:STRING=lib/python3/dist-packages \
  "-DCMAKE_C_FLAGS=$hardening" "-DCMAKE_CXX_FLAGS=$hardening" "-DCMAKE_C_FLAGS_RELEASE=$release" \
  "-DCMAKE_CXX_FLAGS_RELEASE=$release" "-DCMAKE_EXE_LINKER_FLAGS=$link" \
  "-DCMAKE_SHARED_LINKER_FLAGS=$link" "-DCMAKE_MODULE_LINKER_FLAGS=$link" > "$build/configure.log" ||
  { tail -30 "$build/configure.log"; die "cmake could not configure $build (log: $build/configure.log)"; }
step "build ($jobs jobs)"
ninja -C "$build" -j"$jobs" all

# The version: CMake's project(VERSION) is the upstream part and must match the changelog.
version=$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$build/CMakeCache.txt")
work=$build/deb
rm -rf "$work"
mkdir -p "$work/debian"
cp packaging/debian/control packaging/debian/changelog "$work/debian/"
deb_version=$(cd "$work" && dpkg-parsechangelog -SVersion)
[[ ${deb_version%-*} == "$version" ]] ||
  die "packaging/debian/changelog is at $deb_version, the project (CMakeLists.txt) at $version: add a changelog entry $version-1"

stage=$work/debian/foveal
step "install into $stage"
DESTDIR=$stage cmake --install "$build" --strip > "$work/install.log" ||
  { tail -30 "$work/install.log"; die "cmake --install failed (log: $work/install.log)"; }
doc=$stage/usr/share/doc/foveal
mkdir -p "$doc" "$stage/DEBIAN"
cp packaging/debian/copyright "$doc/"
gzip -9n < packaging/debian/changelog > "$doc/changelog.Debian.gz"
mkdir -p "$stage/usr/share/man/man1" "$stage/usr/share/lintian/overrides"
cp packaging/debian/lintian-overrides "$stage/usr/share/lintian/overrides/foveal"
for page in packaging/debian/man/*.1; do
  target=$stage/usr/share/man/man1/${page##*/}.gz
  gzip -9n < "$page" > "$target"
done
cp packaging/debian/postinst packaging/debian/prerm packaging/debian/triggers packaging/debian/shlibs "$stage/DEBIAN/"
chmod 755 "$stage/DEBIAN/postinst" "$stage/DEBIAN/prerm"
chmod 644 "$stage/DEBIAN/triggers" "$stage/DEBIAN/shlibs"

step "dependencies (dpkg-shlibdeps) and control file (dpkg-gencontrol)"
mapfile -t elves < <(find "$stage/usr" -type f \( -perm -u+x -o -name '*.so*' \) -exec sh -c \
  'head -c4 "$1" | grep -q "^.ELF" && echo "$1"' sh {} \;)
((${#elves[@]})) || die "the staging folder $stage has no ELF file: did the install run?"
strip --remove-section=.comment --remove-section=.note "${elves[@]}"  # as dh_strip: the compiler's notes
libdir=$(find "$stage/usr/lib" -name 'libfoveal-client.so.*' -printf '%h\n' | head -1)
(cd "$work" && dpkg-shlibdeps -xfoveal -l"$libdir" -Tdebian/substvars "${elves[@]}") ||
  die "dpkg-shlibdeps failed (is every library the binaries link installed from a Debian package?)"
(cd "$work" && dpkg-gencontrol -pfoveal -Pdebian/foveal -Tdebian/substvars -fdebian/files)
(cd "$stage" && find usr -type f -print0 | sort -z | xargs -0 md5sum) > "$stage/DEBIAN/md5sums"
chmod 644 "$stage/DEBIAN/control" "$stage/DEBIAN/md5sums"

arch=$(dpkg-architecture -qDEB_HOST_ARCH 2>/dev/null || dpkg --print-architecture)
deb=$out/foveal_${deb_version}_${arch}.deb
step "dpkg-deb: $deb"
SOURCE_DATE_EPOCH=$(cd "$work" && dpkg-parsechangelog -STimestamp) \
  dpkg-deb --root-owner-group -Zxz --build "$stage" "$deb" > /dev/null
sed -n 's/^\(Installed-Size\|Depends\|Recommends\): /  \1: /p' "$stage/DEBIAN/control"
if ((lintian)); then
  step "lintian"
  lintian --fail-on error --tag-display-limit 0 "$deb" | tee "$work/lintian.log" ||
    die "lintian reports errors (above; log: $work/lintian.log)"
  echo "lintian: $(grep -c '^E:' "$work/lintian.log" || true) errors, $(grep -c '^W:' "$work/lintian.log" || true) warnings"
fi
echo "$deb"
