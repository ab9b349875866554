// foveal-client against what another user plants at a victim's block name (issue 38
// item 1): a FIFO made `mkfifo -m 666 /dev/shm/foveal-fovea-<victim uid>` hung the
// victim's foveal_client_open, and with it every OpenXR app using the layer, until a
// writer came. Each case runs for real: a second user the test creates plants the thing
// in a private /dev/shm, and the victim (another created user, or root) opens its default
// block in a child under an alarm. The open must come back with NOT_FOVEALDS, naming
// what it found; an open that waits is killed by the alarm and reported as a hang.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <optional>
#include <string>

#include "foveal/client.h"
#include "foveal/core/clock.hpp"
#include "foveal/runtime/fovea_shm.hpp"
#include "foveal/runtime/fovea_shm_layout.h"
#include "other_user.hpp"

namespace {

using foveal::test::TempUser;

/// Generous: a refused open takes microseconds; only a hang reaches it.
constexpr unsigned kHangGuardS = 30;
constexpr int kHung = 128 + SIGALRM;

/// What the victim's open said.
struct Outcome {
  int status = -1;  // the outermost child's exit: 0, kHung, or a set-up failure (1x as attacker, 2x as victim)
  int code = -1;    // err.code, or 0 when it opened
  std::string message;
};

/// A block with a live writer's header and a valid fovea, as foveald would leave it:
/// only who owns it and its mode tell it from foveald's. `mode` is set exactly.
int plant_block(const std::string& path, mode_t mode) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode);
  if (fd < 0 || ::fchmod(fd, mode) != 0 || ::ftruncate(fd, FOVEAL_SHM_V3_SIZE) != 0) return 13;
  unsigned char block[FOVEAL_SHM_V3_SIZE] = {};
  const auto put = [&](std::size_t offset, const auto& v) { std::memcpy(block + offset, &v, sizeof v); };
  put(FOVEAL_SHM_MAGIC_OFFSET, std::uint32_t{FOVEAL_SHM_MAGIC});
  put(FOVEAL_SHM_VERSION_OFFSET, std::uint32_t{3});
  put(FOVEAL_SHM_SIZE_OFFSET, std::uint32_t{FOVEAL_SHM_V3_SIZE});
  // A second ahead of now: still "live" (the reader allows 2 s ahead) when the victim
  // looks, however slowly this machine gets there.
  put(FOVEAL_SHM_HEARTBEAT_OFFSET, std::int64_t{foveal::monotonic_now_ns() + foveal::kNsPerSec});
  put(FOVEAL_SHM_WRITER_STATE_OFFSET, std::uint32_t{FOVEAL_SHM_WRITER_LIVE});
  const bool written = ::pwrite(fd, block, sizeof block, 0) == static_cast<ssize_t>(sizeof block);
  ::close(fd);
  return written ? 0 : 14;
}

/// Things another user can put at a name in /dev/shm (a sticky, world-writable folder).
using Plant = std::function<int(const std::string& path)>;

int plant_fifo(const std::string& path) {
  return ::mkfifo(path.c_str(), 0666) == 0 && ::chmod(path.c_str(), 0666) == 0 ? 0 : 13;
}

/// A link to a FIFO of the attacker's: followed, it would hang the same way.
int plant_symlink(const std::string& path) {
  const std::string target = "/dev/shm/attacker-fifo";
  if (::mkfifo(target.c_str(), 0666) != 0 || ::chmod(target.c_str(), 0666) != 0) return 13;
  return ::symlink(target.c_str(), path.c_str()) == 0 ? 0 : 14;
}

/// Plants with `plant` as `attacker` at `victim`'s default block name (root's when victim
/// is null), in a private /dev/shm, then opens it as the victim. Before the victim opens,
/// `victim_setup` runs as the victim (its own block, for the control case).
Outcome plant_and_open(const TempUser& attacker, const TempUser* victim, const Plant& plant,
                       const std::function<int(const std::string& name)>& victim_setup = {}) {
  int fds[2];
  if (::pipe(fds) != 0) return {};
  const int status = foveal::test::in_child([&] {
    ::close(fds[0]);
    if (!foveal::test::private_tmpfs("/dev/shm")) return 10;
    ::unsetenv("FOVEAL_SHM_NAME");  // the default name, the one an attacker can guess
    const uid_t victim_uid = victim ? victim->uid() : 0;
    const std::string name = "/foveal-fovea-" + std::to_string(victim_uid);
    if (plant) {
      const int planted = foveal::test::in_child([&] { return foveal::test::become(attacker) ? plant("/dev/shm" + name) : 11; });
      if (planted != 0) return planted;
    }
    return foveal::test::in_child([&] {
      if (victim && !foveal::test::become(*victim)) return 20;
      if (victim_setup && victim_setup(name) != 0) return 21;
      ::alarm(kHangGuardS);  // default action: the child dies, and the parent sees the hang
      foveal_error err{-1, "untouched"};
      foveal_client* c = foveal_client_open(nullptr, &err);
      ::alarm(0);
      const std::string said = c ? "0\nopened" : std::to_string(err.code) + "\n" + err.message;
      foveal_client_close(c);
      return ::write(fds[1], said.data(), said.size()) == static_cast<ssize_t>(said.size()) ? 0 : 22;
    });
  });
  ::close(fds[1]);
  std::string said;
  char buf[512];
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) said.append(buf, static_cast<std::size_t>(n));
  ::close(fds[0]);
  Outcome o;
  o.status = status;
  const auto nl = said.find('\n');
  if (nl != std::string::npos) {
    o.code = std::atoi(said.substr(0, nl).c_str());
    o.message = said.substr(nl + 1);
  }
  return o;
}

void expect_refused(const Outcome& o, const std::string& naming) {
  ASSERT_NE(o.status, kHung) << "foveal_client_open did not return within " << kHangGuardS << " s: it waits on what was planted";
  ASSERT_EQ(o.status, 0) << "set-up failed in a child (1x as the attacker, 2x as the victim)";
  EXPECT_EQ(o.code, FOVEAL_ERR_NOT_FOVEALDS) << o.message;
  EXPECT_NE(o.message.find(naming), std::string::npos) << o.message;
}

class FovealClientOtherUser : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!foveal::test::is_root()) GTEST_SKIP() << "needs root to create a second user (useradd); CI runs the tests as root";
    ASSERT_TRUE(attacker_.ok() && victim_.ok()) << "useradd failed";
  }
  TempUser attacker_, victim_;
};

TEST_F(FovealClientOtherUser, AFifoAtTheVictimsNameIsRefusedAtOnceNotWaitedOn) {
  SCOPED_TRACE("a user as the victim");
  expect_refused(plant_and_open(attacker_, &victim_, plant_fifo), "is a FIFO");
  SCOPED_TRACE("root as the victim");
  expect_refused(plant_and_open(attacker_, nullptr, plant_fifo), "is a FIFO");
}

TEST_F(FovealClientOtherUser, ASymbolicLinkAtTheVictimsNameIsNotFollowed) {
  expect_refused(plant_and_open(attacker_, &victim_, plant_symlink), "symbolic link");
  expect_refused(plant_and_open(attacker_, nullptr, plant_symlink), "symbolic link");
}

TEST_F(FovealClientOtherUser, TheAttackersOwnBlockIsRefusedEvenByRoot) {
  const std::string owner = "belongs to uid " + std::to_string(attacker_.uid());
  // Open to all: a reader would take forged gaze from it.
  for (const mode_t mode : {mode_t{0666}, mode_t{0644}}) {
    SCOPED_TRACE("mode " + std::to_string(mode));
    const Plant plant = [mode](const std::string& path) { return plant_block(path, mode); };
    expect_refused(plant_and_open(attacker_, &victim_, plant), owner);
    expect_refused(plant_and_open(attacker_, nullptr, plant), owner);
  }
  // 0600: the victim user cannot open it at all; root could, and must not take it.
  const Plant private_block = [](const std::string& path) { return plant_block(path, 0600); };
  expect_refused(plant_and_open(attacker_, &victim_, private_block), "permission denied");
  expect_refused(plant_and_open(attacker_, nullptr, private_block), owner);
}

TEST_F(FovealClientOtherUser, TheVictimsOwnBlockStillOpens) {
  // The control: foveald's own block at the same name, in the same set-up, opens.
  const auto own_block = [](const std::string& name) {
    static std::optional<foveal::FoveaShm> keep;  // lives until the child exits
    auto w = foveal::FoveaShm::create(name);
    if (!w) return 1;
    keep.emplace(std::move(*w));
    return 0;
  };
  for (const TempUser* victim : {static_cast<const TempUser*>(&victim_), static_cast<const TempUser*>(nullptr)}) {
    const Outcome o = plant_and_open(attacker_, victim, {}, own_block);
    ASSERT_EQ(o.status, 0);
    EXPECT_EQ(o.code, 0) << o.message;
  }
}

}  // namespace
