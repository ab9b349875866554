// foveal bench merge's shard.json reader: a clean error or a shard naming only its kind's tables.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return foveal::fuzz::shard(data, size);
}
