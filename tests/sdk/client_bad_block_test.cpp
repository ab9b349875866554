// foveal-client against blocks that foveald never leaves behind: truncated under a
// client's mapping (SIGBUS on the old code), values out of the ranges foveald writes
// (NaN pixels, confidence 1e30, unknown states), heartbeats no clock gives and writer
// states that are neither live nor stopped, sample times no clock gives and view
// tangents past any display's. Each read says BAD_DATA; nothing crashes, and no block is
// left in /dev/shm, not even by a test whose process dies of SIGBUS.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "foveal/client.h"
#include "foveal/core/clock.hpp"
#include "foveal/runtime/fovea_shm_layout.h"
#include "shm_names.hpp"

namespace {

/// This run's blocks are named after one tag, the pid of the test process that made the
/// first, handed to death tests' children through the environment (they re-run the test
/// in a new process), so that leftovers() finds exactly what this run left.
const std::string& run_tag() {
  static const std::string tag = [] {
    if (const char* t = std::getenv("FOVEAL_BAD_BLOCK_RUN"); t && *t) return std::string(t);
    std::string t = std::to_string(::getpid());
    ::setenv("FOVEAL_BAD_BLOCK_RUN", t.c_str(), 0);
    return t;
  }();
  return tag;
}

std::string block_prefix() { return "foveal-bad-block-" + run_tag() + "-"; }

/// The names in /dev/shm this run made and did not remove.
std::vector<std::string> leftovers() { return foveal::test::shm_leftovers(block_prefix()); }

/// After all the tests of this process (each ctest test is one process), nothing of
/// this run's is left in /dev/shm.
struct BadBlockPrefix {
  std::string operator()() const { return block_prefix(); }
};
[[maybe_unused]] const auto* const g_no_block_left_behind =
    ::testing::AddGlobalTestEnvironment(new foveal::test::NoShmLeftBehind<BadBlockPrefix>);

/// A whole version-3 block as a live foveald leaves it, made by hand so that each test can
/// break one value.
class CraftedBlock {
 public:
  CraftedBlock() {
    name_ = "/" + block_prefix() + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name();
    ::shm_unlink(name_.c_str());
    fd_ = ::shm_open(name_.c_str(), O_RDWR | O_CREAT | O_EXCL, 0600);
    if (fd_ < 0 || ::ftruncate(fd_, FOVEAL_SHM_V3_SIZE) != 0) return;
    void* m = ::mmap(nullptr, FOVEAL_SHM_V3_SIZE, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, 0);
    if (m == MAP_FAILED) return;
    p_ = static_cast<unsigned char*>(m);
    put<std::uint32_t>(FOVEAL_SHM_VERSION_OFFSET, 3);
    put<std::uint32_t>(FOVEAL_SHM_SIZE_OFFSET, FOVEAL_SHM_V3_SIZE);
    put<std::int64_t>(FOVEAL_SHM_HEARTBEAT_OFFSET, foveal::monotonic_now_ns());
    put<std::uint32_t>(FOVEAL_SHM_WRITER_PID_OFFSET, static_cast<std::uint32_t>(::getpid()));
    put<std::uint32_t>(FOVEAL_SHM_WRITER_STATE_OFFSET, FOVEAL_SHM_WRITER_LIVE);
    foveal_shm_fovea f{};
    f.t_ns = 5;
    f.eye_width = 1440;
    f.eye_height = 1600;
    f.x[0] = 720;
    f.y[0] = 800;
    f.x[1] = 1440;  // the viewport's edge is inside it
    f.y[1] = 0;
    f.confidence[0] = 1;
    f.confidence[1] = 0;
    f.state[1] = FOVEAL_STATE_LOST;
    f.frame = 1;
    fovea(f);
    settings({2.0, 3.0, 0.3, -1.0, 1, 0, 1});
    foveal_shm_view v{{-1.2f, -1.1f}, {1.1f, 1.2f}, {-1.3f, -1.3f}, {1.3f, 1.3f}, 0.063f, 1};
    view(v);
    put<std::uint32_t>(FOVEAL_SHM_MAGIC_OFFSET, FOVEAL_SHM_MAGIC);
  }
  ~CraftedBlock() {
    if (p_) ::munmap(p_, FOVEAL_SHM_V3_SIZE);
    if (fd_ >= 0) ::close(fd_);
    unlink();
  }
  /// Removes the name now (a mapping of the block stays valid): for a process that will
  /// not reach the destructor.
  void unlink() { ::shm_unlink(name_.c_str()); }
  bool ok() const { return p_ != nullptr; }
  const char* name() const { return name_.c_str(); }
  int fd() const { return fd_; }

  template <class T>
  void put(std::size_t offset, T v) {
    std::memcpy(p_ + offset, &v, sizeof v);
  }
  void fovea(const foveal_shm_fovea& f) { std::memcpy(p_ + FOVEAL_SHM_FOVEA_WORDS_OFFSET, &f, sizeof f); }
  void settings(const foveal_shm_settings& s) { std::memcpy(p_ + FOVEAL_SHM_SETTINGS_WORDS_OFFSET, &s, sizeof s); }
  void view(const foveal_shm_view& v) { std::memcpy(p_ + FOVEAL_SHM_VIEW_WORDS_OFFSET, &v, sizeof v); }
  foveal_shm_fovea fovea() const {
    foveal_shm_fovea f;
    std::memcpy(&f, p_ + FOVEAL_SHM_FOVEA_WORDS_OFFSET, sizeof f);
    return f;
  }
  foveal_shm_settings settings() const {
    foveal_shm_settings s;
    std::memcpy(&s, p_ + FOVEAL_SHM_SETTINGS_WORDS_OFFSET, sizeof s);
    return s;
  }
  foveal_shm_view view() const {
    foveal_shm_view v;
    std::memcpy(&v, p_ + FOVEAL_SHM_VIEW_WORDS_OFFSET, sizeof v);
    return v;
  }

 private:
  std::string name_;
  int fd_ = -1;
  unsigned char* p_ = nullptr;
};

struct Client {
  foveal_client* c = nullptr;
  foveal_error err{-1, "untouched"};
  explicit Client(const char* name) { c = foveal_client_open(name, &err); }
  ~Client() { foveal_client_close(c); }
};

TEST(FovealClientBadBlock, TheCraftedBlockReadsWhenNothingIsBroken) {
  CraftedBlock b;
  ASSERT_TRUE(b.ok());
  Client o(b.name());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  foveal_fovea f{};
  foveal_settings s{};
  foveal_view v{};
  EXPECT_EQ(foveal_client_read(o.c, &f), FOVEAL_OK);
  EXPECT_EQ(foveal_client_settings(o.c, &s), FOVEAL_OK);
  EXPECT_EQ(foveal_client_view(o.c, &v), FOVEAL_OK);
}

TEST(FovealClientBadBlock, ABlockTruncatedUnderTheMappingIsBadDataNotSigbus) {
  CraftedBlock b;
  ASSERT_TRUE(b.ok());
  Client o(b.name());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  foveal_fovea f{};
  ASSERT_EQ(foveal_client_read(o.c, &f), FOVEAL_OK);
  ASSERT_EQ(::ftruncate(b.fd(), 0), 0);  // the mapped page is gone: a load from it is SIGBUS
  f.frame = 77;
  EXPECT_EQ(foveal_client_read(o.c, &f), FOVEAL_ERR_BAD_DATA);
  EXPECT_EQ(f.frame, 77u) << "*out is unchanged";
  foveal_settings s{};
  foveal_view v{};
  EXPECT_EQ(foveal_client_settings(o.c, &s), FOVEAL_ERR_BAD_DATA);
  EXPECT_EQ(foveal_client_view(o.c, &v), FOVEAL_ERR_BAD_DATA);
  // Grown back, the client still says so (it stays bound to the block it lost): open anew.
  ASSERT_EQ(::ftruncate(b.fd(), FOVEAL_SHM_V3_SIZE), 0);
  EXPECT_EQ(foveal_client_read(o.c, &f), FOVEAL_ERR_BAD_DATA);
  EXPECT_NE(std::string(foveal_error_message(FOVEAL_ERR_BAD_DATA)).find("cut short"), std::string::npos);
}

int g_program_handler_calls = 0;
void program_handler(int) { ++g_program_handler_calls; }

TEST(FovealClientBadBlock, ASigbusOutsideAReadReachesTheHandlerTheProgramHad) {
  struct sigaction mine{};
  mine.sa_handler = program_handler;
  sigemptyset(&mine.sa_mask);
  ASSERT_EQ(::sigaction(SIGBUS, &mine, nullptr), 0);
  {
    CraftedBlock b;
    ASSERT_TRUE(b.ok());
    Client o(b.name());  // puts the library's handler in front of the program's
    ASSERT_NE(o.c, nullptr) << o.err.message;
    struct sigaction now{};
    ::sigaction(SIGBUS, nullptr, &now);
    EXPECT_NE(now.sa_handler, program_handler);
    g_program_handler_calls = 0;
    ::raise(SIGBUS);
    EXPECT_EQ(g_program_handler_calls, 1);
  }
  // Leave the library chained to the default action, not to this test's handler (which
  // returns: a real fault would come back forever).
  struct sigaction dfl{};
  dfl.sa_handler = SIG_DFL;
  ::sigaction(SIGBUS, &dfl, nullptr);
  CraftedBlock b;
  Client again(b.name());
  EXPECT_NE(again.c, nullptr) << again.err.message;
}

TEST(FovealClientBadBlock, ASigbusOutsideAReadStillKillsAProgramWithoutAHandler) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  run_tag();  // set before the child starts, which inherits it
  EXPECT_DEATH(
      {
        struct sigaction dfl{};
        dfl.sa_handler = SIG_DFL;
        ::sigaction(SIGBUS, &dfl, nullptr);
        CraftedBlock b;
        Client o(b.name());
        b.unlink();  // this process dies below, before any destructor: the name goes now
        if (!o.c) std::_Exit(0);  // the death test then fails: it must die of SIGBUS
        ::raise(SIGBUS);
        std::_Exit(0);
      },
      "");
  // The child died without cleaning up: what it made must be gone all the same.
  const auto left = leftovers();
  EXPECT_TRUE(left.empty()) << "the child that died of SIGBUS left" << foveal::test::shm_paths(left);
}

/// Reads through a fresh client after `breakage`, and returns what `read` says.
int after(const std::function<void(CraftedBlock&)>& breakage, const std::function<int(foveal_client*)>& read) {
  CraftedBlock b;
  if (!b.ok()) return -1;
  Client o(b.name());
  if (!o.c) return -2;
  breakage(b);
  return read(o.c);
}

int read_fovea(foveal_client* c) {
  foveal_fovea f{};
  return foveal_client_read(c, &f);
}
int read_settings(foveal_client* c) {
  foveal_settings s{};
  return foveal_client_settings(c, &s);
}
int read_view(foveal_client* c) {
  foveal_view v{};
  return foveal_client_view(c, &v);
}

TEST(FovealClientBadBlock, FoveaValuesFovealdNeverWritesAreBadData) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const std::function<void(foveal_shm_fovea&)> breakages[] = {
      [&](foveal_shm_fovea& f) { f.x[0] = nan; },
      [&](foveal_shm_fovea& f) { f.y[1] = inf; },
      [&](foveal_shm_fovea& f) { f.x[1] = -inf; },
      [&](foveal_shm_fovea& f) { f.x[0] = 1441; },   // off the viewport
      [&](foveal_shm_fovea& f) { f.y[0] = -0.5f; },
      [&](foveal_shm_fovea& f) { f.confidence[0] = 1e30f; },
      [&](foveal_shm_fovea& f) { f.confidence[1] = nan; },
      [&](foveal_shm_fovea& f) { f.confidence[1] = -0.1f; },
      [&](foveal_shm_fovea& f) { f.state[0] = 0xFFFFFFFFu; },
      [&](foveal_shm_fovea& f) { f.state[1] = 5; },
      [&](foveal_shm_fovea& f) { f.eye_width = 0; },
      [&](foveal_shm_fovea& f) { f.eye_height = 0; },
      [&](foveal_shm_fovea& f) { f.eye_width = 0xFFFFFFFFu; },
  };
  int i = 0;
  for (const auto& breakage : breakages) {
    SCOPED_TRACE("breakage " + std::to_string(i++));
    EXPECT_EQ(after([&](CraftedBlock& b) { auto f = b.fovea(); breakage(f); b.fovea(f); }, read_fovea), FOVEAL_ERR_BAD_DATA);
  }
  // Frame 0 is "nothing yet", whatever the rest holds.
  EXPECT_EQ(after([](CraftedBlock& b) { auto f = b.fovea(); f.frame = 0; f.eye_width = 0; b.fovea(f); }, read_fovea),
            FOVEAL_ERR_NO_DATA);
}

TEST(FovealClientBadBlock, SettingsFovealdNeverWritesAreBadData) {
  const double nan = std::nan("");
  const std::function<void(foveal_shm_settings&)> breakages[] = {
      [](foveal_shm_settings& s) { s.dominant_eye = 7; },
      [&](foveal_shm_settings& s) { s.sigma_d = nan; },
      [](foveal_shm_settings& s) { s.sigma_d = 0.5; },
      [](foveal_shm_settings& s) { s.sigma_nd = 1.5; },  // below sigma_d
      [](foveal_shm_settings& s) { s.sigma_nd = 1e300; },
      [&](foveal_shm_settings& s) { s.f_x = nan; },
      [](foveal_shm_settings& s) { s.f_y = 0; },
      [](foveal_shm_settings& s) { s.f_y = -std::numeric_limits<double>::infinity(); },
      [](foveal_shm_settings& s) { s.f_x = 1e9; },
      [](foveal_shm_settings& s) { s.generation = 0; },  // a fovea is out, so the settings came before it
  };
  int i = 0;
  for (const auto& breakage : breakages) {
    SCOPED_TRACE("breakage " + std::to_string(i++));
    EXPECT_EQ(after([&](CraftedBlock& b) { auto s = b.settings(); breakage(s); b.settings(s); }, read_settings),
              FOVEAL_ERR_BAD_DATA);
  }
  // Generation 0 before the first fovea: a foveald still starting.
  EXPECT_EQ(after([](CraftedBlock& b) {
              auto s = b.settings();
              s.generation = 0;
              b.settings(s);
              auto f = b.fovea();
              f.frame = 0;
              b.fovea(f);
            },
                  read_settings),
            FOVEAL_ERR_NO_DATA);
}

TEST(FovealClientBadBlock, AViewFovealdNeverWritesIsBadData) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const std::function<void(foveal_shm_view&)> breakages[] = {
      [&](foveal_shm_view& v) { v.tan_left[0] = nan; },
      [&](foveal_shm_view& v) { v.tan_top[1] = inf; },
      [](foveal_shm_view& v) { v.tan_left[1] = 1.5f; },   // left of it is right of the right edge
      [](foveal_shm_view& v) { v.tan_bottom[0] = 1.3f; },  // bottom == top
      [](foveal_shm_view& v) { v.ipd_m = 0; },
      [](foveal_shm_view& v) { v.ipd_m = 0.21f; },
      [&](foveal_shm_view& v) { v.ipd_m = nan; },
      [](foveal_shm_view& v) { v.published = 7; },
  };
  int i = 0;
  for (const auto& breakage : breakages) {
    SCOPED_TRACE("breakage " + std::to_string(i++));
    EXPECT_EQ(after([&](CraftedBlock& b) { auto v = b.view(); breakage(v); b.view(v); }, read_view), FOVEAL_ERR_BAD_DATA);
  }
  EXPECT_EQ(after([](CraftedBlock& b) { auto v = b.view(); v.published = 0; b.view(v); }, read_view), FOVEAL_ERR_NO_DATA);
}

TEST(FovealClientBadBlock, SampleTimesNoClockGivesAreBadDataAndOldOnesRead) {
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max(), kMin = std::numeric_limits<std::int64_t>::min();
  const std::int64_t now = foveal::monotonic_now_ns();
  // INT64_MIN would overflow `now - t_ns`; an hour ahead would keep a frozen gaze fresh
  // for an hour; 5 s ahead is more than any clock mapping is off.
  const std::int64_t bad[] = {kMin, -1, 0, kMax, now + 3600 * foveal::kNsPerSec, now + 5 * foveal::kNsPerSec};
  for (const std::int64_t t : bad) {
    SCOPED_TRACE("t_ns " + std::to_string(t));
    CraftedBlock b;
    ASSERT_TRUE(b.ok());
    Client o(b.name());
    ASSERT_NE(o.c, nullptr) << o.err.message;
    auto f = b.fovea();
    f.t_ns = t;
    b.fovea(f);
    foveal_fovea out{};
    out.frame = 77;
    EXPECT_EQ(foveal_client_read(o.c, &out), FOVEAL_ERR_BAD_DATA);
    EXPECT_EQ(out.frame, 77u) << "*out is unchanged";
  }
  // A sample from long ago (a paused foveald) and one a moment ahead (a tracker clock
  // mapped a little early) are times foveald writes: the reader judges freshness.
  for (const std::int64_t t : {std::int64_t{1}, now, now + foveal::kNsPerSec / 2}) {
    SCOPED_TRACE("t_ns " + std::to_string(t));
    EXPECT_EQ(after([&](CraftedBlock& b) { auto f = b.fovea(); f.t_ns = t; b.fovea(f); }, read_fovea), FOVEAL_OK);
  }
}

TEST(FovealClientBadBlock, ViewTangentsPastTheDisplayModelsBoundsAreBadData) {
  const std::function<void(foveal_shm_view&)> breakages[] = {
      [](foveal_shm_view& v) { v.tan_left[0] = -1e19f; },
      [](foveal_shm_view& v) { v.tan_right[1] = 1e19f; },
      [](foveal_shm_view& v) { v.tan_top[0] = 100.5f; },
      [](foveal_shm_view& v) { v.tan_bottom[1] = -101.0f; },
      [](foveal_shm_view& v) { v.tan_left[0] = v.tan_right[0] - 0.005f; },  // narrower than any display's 0.01
      [](foveal_shm_view& v) { v.tan_bottom[1] = v.tan_top[1] - 0.001f; },
  };
  int i = 0;
  for (const auto& breakage : breakages) {
    SCOPED_TRACE("breakage " + std::to_string(i++));
    EXPECT_EQ(after([&](CraftedBlock& b) { auto v = b.view(); breakage(v); b.view(v); }, read_view), FOVEAL_ERR_BAD_DATA);
  }
  // Wide but inside the bounds foveald's display model takes (|tan| <= 100): it reads.
  EXPECT_EQ(after([](CraftedBlock& b) {
              foveal_shm_view v{{-100.0f, -50.0f}, {50.0f, 100.0f}, {-100.0f, -0.01f}, {0.0f, 100.0f}, 0.063f, 1};
              b.view(v);
            },
                  read_view),
            FOVEAL_OK);
}

TEST(FovealClientBadBlock, HeartbeatsNoClockGivesAndUnknownWriterStatesAreBadData) {
  const std::int64_t beats[] = {std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::min(), -1,
                                foveal::monotonic_now_ns() + 60 * foveal::kNsPerSec};
  for (const std::int64_t beat : beats) {
    SCOPED_TRACE("heartbeat " + std::to_string(beat));
    const auto frozen = [&](CraftedBlock& b) { b.put<std::int64_t>(FOVEAL_SHM_HEARTBEAT_OFFSET, beat); };
    EXPECT_EQ(after(frozen, read_fovea), FOVEAL_ERR_BAD_DATA);
    EXPECT_EQ(after(frozen, read_settings), FOVEAL_ERR_BAD_DATA);
    EXPECT_EQ(after(frozen, read_view), FOVEAL_ERR_BAD_DATA);
    CraftedBlock b;
    ASSERT_TRUE(b.ok());
    frozen(b);
    Client o(b.name());
    EXPECT_EQ(o.c, nullptr);
    EXPECT_EQ(o.err.code, FOVEAL_ERR_BAD_DATA);
    EXPECT_NE(std::string(o.err.message).find("heartbeat " + std::to_string(beat)), std::string::npos) << o.err.message;
  }
  for (const std::uint32_t state : {0u, 3u, 99u, 0xFFFFFFFFu}) {
    SCOPED_TRACE("writer state " + std::to_string(state));
    const auto odd = [&](CraftedBlock& b) { b.put<std::uint32_t>(FOVEAL_SHM_WRITER_STATE_OFFSET, state); };
    EXPECT_EQ(after(odd, read_fovea), FOVEAL_ERR_BAD_DATA);
    EXPECT_EQ(after(odd, read_settings), FOVEAL_ERR_BAD_DATA);
    CraftedBlock b;
    ASSERT_TRUE(b.ok());
    odd(b);
    Client o(b.name());
    EXPECT_EQ(o.c, nullptr);
    EXPECT_EQ(o.err.code, FOVEAL_ERR_BAD_DATA);
    EXPECT_NE(std::string(o.err.message).find("writer state " + std::to_string(state)), std::string::npos) << o.err.message;
  }
  // A heartbeat a moment ahead of this reader's clock is a writer that beat just now.
  EXPECT_EQ(after([](CraftedBlock& b) { b.put<std::int64_t>(FOVEAL_SHM_HEARTBEAT_OFFSET, foveal::monotonic_now_ns() + 1000); },
                  read_fovea),
            FOVEAL_OK);
}

}  // namespace
