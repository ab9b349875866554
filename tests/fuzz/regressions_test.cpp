// Replays every seed and every saved crash input through the fuzz targets' bodies in
// the normal (and sanitizer) builds, so a fixed crash stays fixed without libFuzzer.
#include <gtest/gtest.h>

#include <filesystem>

#include "fuzz_targets.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

using Target = int (*)(const std::uint8_t*, std::size_t);

std::size_t replay_dir(const std::string& dir, Target target) {
  std::size_t n = 0;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string bytes = test::read_file(entry.path().string());
    SCOPED_TRACE(entry.path().string());
    EXPECT_EQ(target(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), 0);
    ++n;
  }
  return n;
}

void replay(const std::string& name, Target target) {
  const std::string root = test::source_path("tests/fuzz/");
  const std::size_t seeds = replay_dir(root + "corpus/" + name, target);
  replay_dir(root + "regressions/" + name, target);
  EXPECT_GT(seeds, 0u) << "no seed corpus for " << name;
}

TEST(FuzzRegressions, GazeLog) { replay("gaze_log", fuzz::gaze_log); }
TEST(FuzzRegressions, Import) { replay("import", fuzz::import); }
TEST(FuzzRegressions, Profile) { replay("profile", fuzz::profile); }
TEST(FuzzRegressions, Control) { replay("control", fuzz::control); }
TEST(FuzzRegressions, Display) { replay("display", fuzz::display); }
TEST(FuzzRegressions, Shard) { replay("shard", fuzz::shard); }
#ifdef FOVEAL_HAVE_GLTF
TEST(FuzzRegressions, Gltf) { replay("gltf", fuzz::gltf); }
#endif
#ifdef FOVEAL_HAVE_HID
TEST(FuzzRegressions, Hid) { replay("hid", fuzz::hid); }
#endif
#ifdef FOVEAL_HAVE_USB
TEST(FuzzRegressions, Psvr2) { replay("psvr2", fuzz::psvr2); }
#endif
#if defined(FOVEAL_HAVE_USB) && defined(FOVEAL_HAVE_VIVE)
TEST(FuzzRegressions, Hmd) { replay("hmd", fuzz::hmd); }
#endif
#ifdef FOVEAL_HAVE_VIVE
TEST(FuzzRegressions, Vive) { replay("vive", fuzz::vive); }
#endif

}  // namespace
}  // namespace foveal
