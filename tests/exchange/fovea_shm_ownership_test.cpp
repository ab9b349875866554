// Who may own the fovea block (docs/fovea-shm.md): foveald creates it O_EXCL, 0600, and
// takes over an existing one only when it is this user's, 0600, and no live writer
// holds it. Issue 15 item 7 replayed: another user plants a 0666 block first.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>

#include "foveal/runtime/fovea_shm.hpp"
#include "other_user.hpp"

namespace foveal {
namespace {

std::string unique_name() {
  return "/foveal-test-" + std::to_string(::getpid()) + "-" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

/// A block made by hand with `mode`, as a crashed daemon or an attacker leaves it.
void plant_block(const std::string& name, mode_t mode) {
  const int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT | O_EXCL, mode);
  ASSERT_GE(fd, 0) << std::strerror(errno);
  ASSERT_EQ(::fchmod(fd, mode), 0);
  ASSERT_EQ(::ftruncate(fd, sizeof(FoveaShmBlock)), 0);
  ::close(fd);
}

TEST(FoveaShmOwnership, ANewBlockIsExactly0600WhateverTheUmask) {
  const std::string name = unique_name();
  const mode_t old = ::umask(0);
  auto w = FoveaShm::create(name);
  ::umask(old);
  ASSERT_TRUE(w) << w.error().message;
  struct stat st{};
  ASSERT_EQ(::stat(("/dev/shm" + name).c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
}

TEST(FoveaShmOwnership, AStaleBlockOfThisUserIsReused) {
  const std::string name = unique_name();
  plant_block(name, 0600);  // what a crashed foveald leaves
  auto w = FoveaShm::create(name);
  ASSERT_TRUE(w) << w.error().message;
  auto r = FoveaShm::open(name);
  ASSERT_TRUE(r) << r.error().message;
  FoveaFrame f;
  f.t_ns = 42;
  w->publish(f, 100, 100);
  FoveaShmPayload p{};
  ASSERT_TRUE(r->read(p));
  EXPECT_EQ(p.t_ns, 42);
}

TEST(FoveaShmOwnership, ABlockOfThisUserWithAWiderModeIsRefused) {
  const std::string name = unique_name();
  plant_block(name, 0644);
  auto w = FoveaShm::create(name);
  ASSERT_FALSE(w);
  EXPECT_NE(w.error().message.find("shared memory " + name), std::string::npos) << w.error().message;
  EXPECT_NE(w.error().message.find("its mode is 0644, not 0600"), std::string::npos) << w.error().message;
  auto r = FoveaShm::open(name);  // readers refuse what others may write, too
  EXPECT_FALSE(r);
  ::shm_unlink(name.c_str());
}

TEST(FoveaShmOwnership, ASecondWriterIsRefusedWhileTheFirstLives) {
  const std::string name = unique_name();
  auto first = FoveaShm::create(name);
  ASSERT_TRUE(first) << first.error().message;
  auto second = FoveaShm::create(name);
  ASSERT_FALSE(second);
  EXPECT_NE(second.error().message.find("another foveald is publishing there"), std::string::npos)
      << second.error().message;
  EXPECT_TRUE(FoveaShm::open(name)) << "the first one's block is still there";
}

TEST(FoveaShmOwnership, AnotherUsersBlockIsRefused) {
  FOVEAL_REQUIRE_ROOT();
  test::TempUser attacker, victim;
  ASSERT_TRUE(attacker.ok() && victim.ok()) << "useradd failed";
  const int rc = test::in_child([&] {
    if (!test::private_tmpfs("/dev/shm")) return 10;
    const std::string name = "/foveal-fovea-" + std::to_string(victim.uid());
    // The attacker creates the victim's block first, readable and writable by all.
    const int planted = test::in_child([&] {
      if (!test::become(attacker)) return 11;
      const int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT | O_EXCL, 0666);
      if (fd < 0 || ::fchmod(fd, 0666) != 0 || ::ftruncate(fd, sizeof(FoveaShmBlock)) != 0) return 12;
      return 0;
    });
    if (planted != 0) return planted;
    return test::in_child([&] {
      if (!test::become(victim)) return 20;
      if (default_fovea_shm_name() != name) return 21;
      auto w = FoveaShm::create(name);
      if (w) return 22;  // it would publish the live gaze into the attacker's block
      std::fprintf(stderr, "foveald as the victim: %s\n", w.error().message.c_str());
      if (w.error().message.find("belongs to uid " + std::to_string(attacker.uid())) == std::string::npos) return 23;
      if (FoveaShm::open(name)) return 24;  // and a reader does not take the attacker's data for gaze
      return 0;
    });
  });
  EXPECT_EQ(rc, 0) << "see the child's stderr: 1x set-up, 22 the victim published into the planted block, "
                      "23 the refusal does not name the owner, 24 a reader accepted it";
}

}  // namespace
}  // namespace foveal
