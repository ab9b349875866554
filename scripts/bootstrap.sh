#!/usr/bin/env bash
# Installs the Debian 12 packages foveal needs (only those missing), then configures and
# builds it in ./build. Safe to run again: it does only what is left to do.
# Usage: scripts/bootstrap.sh [extra cmake -D options...]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config git ccache
  libhidapi-dev libusb-1.0-0-dev zlib1g-dev  # zlib: the Vive config (docs/headset.md)
  libglfw3-dev libglm-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  libdrm-dev libgbm-dev  # direct mode (EGL on GBM, KMS)
  libtinygltf-dev nlohmann-json3-dev libstb-dev libcli11-dev
  libdraco-dev libmeshoptimizer-dev  # compressed glTF geometry (docs/scenes.md)
  googletest libgtest-dev libbenchmark-dev
  python3 python3-matplotlib python3-numpy python3-scipy  # charts; tests against NumPy/SciPy
  qemu-system-x86 linux-image-amd64 busybox-static cpio kmod  # tests/vm (docs/vm-tests.md)
  xvfb xauth xdotool  # the GLFW window paths, tested on a virtual X server
  clang libclang-rt-14-dev  # libFuzzer targets (scripts/test.sh)
  slurm-wlm munge  # bench sweeps on Slurm: the one-node cluster test (tests/cluster)
  # The OpenXR test runtime: Monado's build deps (scripts/build_monado.sh), then the loader
  libvulkan-dev glslang-tools mesa-vulkan-drivers libx11-xcb-dev libxcb-randr0-dev
  libxrandr-dev libudev-dev libcjson-dev libbsd-dev libsystemd-dev libdbus-1-dev
  libegl1-mesa-dev libwayland-dev wayland-protocols libeigen3-dev xz-utils
  libopenxr-dev libopenxr-loader1 openxr-layer-corevalidation libopenxr-utils
)

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

# The OpenXR tests' runtime (Monado), built once into a cache; exit 3: no snapshot here.
openxr=()
if manifest=$(scripts/build_monado.sh); then
  openxr=("-DFOVEAL_TEST_OPENXR_RUNTIME=${manifest##*$'\n'}")
else
  rc=$?
  ((rc == 3)) || exit "$rc"
  echo "bootstrap: no Monado snapshot and no cached build: the openxr tests will be reported as not run"
fi

source scripts/compiler_cache.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" "${openxr[@]}" "$@"
cmake --build build -j "$(nproc)"
