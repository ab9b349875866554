#!/usr/bin/env bash
# `foveald --version`, `foveal --version`, the Python module's __version__ (from the
# source tree, and as the install writes it) and the pkg-config files against CMake's
# project(VERSION): one number, from one place (cmake/FovealVersion.cmake).
# Usage: version_test.sh VERSION BUILD_DIR SOURCE_DIR PYTHON3
set -euo pipefail
version=$1 build=$2 src=$3 python=$4
fail() { echo "version_test: $*" >&2; exit 1; }
for p in foveald foveal; do
  [[ -x $build/bin/$p ]] || fail "$build/bin/$p is not built (ninja -C $build $p)"
  got=$("$build/bin/$p" --version) || fail "$p --version exited $?"
  [[ $got == "$p $version" ]] || fail "$p --version prints '$got', the project is at $version (CMakeLists.txt project(VERSION))"
  echo "$p --version: $got"
done
got=$(PYTHONPATH=$src/sdk/python "$python" -c 'import foveal; print(foveal.__version__)') ||
  fail "the source tree's Python module does not import"
[[ $got == "$version" ]] || fail "foveal.__version__ (source tree) is '$got', the project is at $version"
echo "foveal.__version__ (source tree): $got"
installed=$build/sdk/python/_install.py
grep -qx "VERSION = \"$version\"" "$installed" || fail "$installed (the installed module's version) does not say VERSION = \"$version\""
for pc in "$build"/sdk/foveal-*.pc; do
  grep -qx "Version: $version" "$pc" || fail "$pc does not say Version: $version"
done
echo "the installed module's _install.py and the .pc files: $version"
