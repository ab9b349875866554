// glTF loading (tinygltf + foveal's checks), CPU only: never a crash, a hang or an
// allocation past the limits; what loads is drawable.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return foveal::fuzz::gltf(data, size);
}
