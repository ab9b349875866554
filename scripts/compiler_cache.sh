# Sourced by scripts/bootstrap.sh and scripts/test.sh: compile through ccache when it is
# installed, with its cache beside Monado's build (FOVEAL_CACHE_DIR), so that a machine
# that keeps ~/.cache between runs recompiles only what changed, in every build tree
# (build, build-asan, build-tsan, build-fuzz) and every clone. Sets `launcher` to the
# cmake arguments (empty without ccache).
launcher=()
if command -v ccache > /dev/null; then
  export CCACHE_DIR=${CCACHE_DIR:-${FOVEAL_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/foveal}/ccache}
  export CCACHE_MAXSIZE=${CCACHE_MAXSIZE:-10G}
  # Paths under the clone are hashed relative to it, and the build directory is not
  # hashed, so a fresh clone elsewhere hits the same entries (its debug info then names
  # the first clone's directory).
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
  export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
