#pragma once
// Shared-memory names the SDK tests make: removed at scope exit whatever the test does
// (a failed ASSERT returns early), and a check, at the end of each test process, that
// none of them is left in /dev/shm.
#include <dirent.h>
#include <sys/mman.h>

#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace foveal::test {

/// A name ("/...") that is shm_unlink'ed when this goes out of scope; a std::string otherwise.
class ScopedShmName : public std::string {
 public:
  explicit ScopedShmName(std::string name) : std::string(std::move(name)) {}
  ~ScopedShmName() { ::shm_unlink(c_str()); }
  ScopedShmName(const ScopedShmName&) = delete;
  ScopedShmName& operator=(const ScopedShmName&) = delete;
};

/// The names in /dev/shm that start with `prefix` (no leading slash).
inline std::vector<std::string> shm_leftovers(const std::string& prefix) {
  std::vector<std::string> found;
  DIR* d = ::opendir("/dev/shm");
  if (!d) return found;
  while (const dirent* e = ::readdir(d))
    if (std::string(e->d_name).rfind(prefix, 0) == 0) found.emplace_back(e->d_name);
  ::closedir(d);
  return found;
}

inline std::string shm_paths(const std::vector<std::string>& names) {
  std::string all;
  for (const auto& n : names) all += " /dev/shm/" + n;
  return all;
}

/// Registered with ::testing::AddGlobalTestEnvironment: after the last test of the
/// process, nothing whose name starts with prefix() is left in /dev/shm.
template <class Prefix>
class NoShmLeftBehind : public ::testing::Environment {
 public:
  void TearDown() override {
    const auto left = shm_leftovers(Prefix{}());
    EXPECT_TRUE(left.empty()) << "left behind:" << shm_paths(left);
  }
};

}  // namespace foveal::test
