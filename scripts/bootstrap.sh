#!/usr/bin/env bash
# Installs the Debian 12 packages foveal needs (only those missing), then configures and
# builds it in ./build. Safe to run again: it does only what is left to do.
# Usage: scripts/bootstrap.sh [--tests] [extra cmake -D options...]
#   without --tests: what the product needs (the daemon, the CLI, the OpenXR layer, the
#     SDK), built without the tests: the README's first command;
#   --tests: also what the test suite needs (GoogleTest, QEMU and a kernel for the VM
#     tests, Xvfb, clang for the fuzzers, Slurm, Monado's build for the OpenXR tests), and
#     the tests and benchmarks built: the README's second command, before scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
tests=0
if [[ "${1:-}" == "-h" || "${1:-}" == "--help" ]]; then
  sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
if [[ "${1:-}" == "--tests" ]]; then
  tests=1
  shift
fi

packages=(
  build-essential cmake ninja-build pkg-config git ccache
  libhidapi-dev libusb-1.0-0-dev zlib1g-dev  # zlib: the Vive config (docs/headset.md)
  libglfw3-dev libglm-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  libdrm-dev libgbm-dev  # direct mode (EGL on GBM, KMS)
  libtinygltf-dev nlohmann-json3-dev libstb-dev libcli11-dev
  libdraco-dev libmeshoptimizer-dev  # compressed glTF geometry (docs/scenes.md)
  python3 python3-matplotlib  # the bench's charts (docs/bench.md)
  libopenxr-dev libopenxr-loader1  # the OpenXR layer and `foveal openxr`
  libvulkan-dev glslang-tools mesa-vulkan-drivers  # the layer's Vulkan composer
)
test_packages=(
  googletest libgtest-dev libbenchmark-dev
  python3-numpy python3-scipy  # tests against NumPy/SciPy
  qemu-system-x86 linux-image-amd64 busybox-static cpio kmod  # tests/vm (docs/vm-tests.md)
  xvfb xauth xdotool  # the GLFW window paths, tested on a virtual X server
  clang libclang-rt-14-dev  # libFuzzer targets (scripts/test.sh)
  slurm-wlm munge  # bench sweeps on Slurm: the one-node cluster test (tests/cluster)
  # The OpenXR test runtime: Monado's build deps (scripts/build_monado.sh), then the
  # loader's validation layer
  libx11-xcb-dev libxcb-randr0-dev
  libxrandr-dev libudev-dev libcjson-dev libbsd-dev libsystemd-dev libdbus-1-dev
  libegl1-mesa-dev libwayland-dev wayland-protocols libeigen3-dev xz-utils
  openxr-layer-corevalidation libopenxr-utils
)
if ((tests)); then packages+=("${test_packages[@]}"); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "bootstrap: installing ${missing[*]}"
  sudo=""
  [[ $(id -u) -eq 0 ]] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -q
  $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

options=()
if ((tests)); then
  # The OpenXR tests' runtime (Monado), built once into a cache; exit 3: no snapshot here.
  if manifest=$(scripts/build_monado.sh); then
    options+=("-DFOVEAL_TEST_OPENXR_RUNTIME=${manifest##*$'\n'}")
  else
    rc=$?
    ((rc == 3)) || exit "$rc"
    echo "bootstrap: no Monado snapshot and no cached build: the openxr tests will be reported as not run"
  fi
  options+=(-DFOVEAL_BUILD_TESTS=ON -DFOVEAL_BUILD_BENCHMARKS=ON)
elif [[ ! -f build/CMakeCache.txt ]]; then
  # A first build without --tests leaves the tests out; a build tree that has them keeps them.
  options+=(-DFOVEAL_BUILD_TESTS=OFF -DFOVEAL_BUILD_BENCHMARKS=OFF)
fi

source scripts/compiler_cache.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" "${options[@]}" "$@"
cmake --build build -j "$(nproc)"
