// foveal-client's prediction (block version 4): the motion foveald publishes with each
// fovea, and foveal_client_predict giving what foveald's own predict_fovea gives; a
// version-3 block still reads, without motion.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>
#include <thread>

#include "foveal/client.h"
#include "foveal/core/clock.hpp"
#include "foveal/runtime/fovea_prediction.hpp"
#include "foveal/runtime/fovea_shm.hpp"
#include "shm_names.hpp"

namespace foveal {
namespace {

std::string name_prefix() { return "foveal-predict-test-" + std::to_string(::getpid()) + "-"; }

test::ScopedShmName unique_name() {
  return test::ScopedShmName("/" + name_prefix() + ::testing::UnitTest::GetInstance()->current_test_info()->name());
}

struct PredictTestPrefix {
  std::string operator()() const { return name_prefix(); }
};
[[maybe_unused]] const auto* const g_no_block_left_behind =
    ::testing::AddGlobalTestEnvironment(new test::NoShmLeftBehind<PredictTestPrefix>);

struct Opened {
  foveal_client* c = nullptr;
  foveal_error err{-1, "untouched"};
  explicit Opened(const char* name) { c = foveal_client_open(name, &err); }
  ~Opened() { foveal_client_close(c); }
};

/// Left eye in pursuit (predictable), right eye in a saccade (held), as the pipeline hands them.
FoveaFrame moving(TimeNs t, float vx) {
  FoveaFrame f;
  f.t_ns = t;
  f.eyes[0] = {{700.0f, 800.0f}, FoveaState::pursuit, 0.9f, {vx, -120.0f}, {4.0f, -1.5f}, true};
  f.eyes[1] = {{300.0f, 900.0f}, FoveaState::saccade, 0.8f, {0.0f, 0.0f}, {0.0f, 0.0f}, false};
  return f;
}

TEST(FovealClientPredict, PredictsToATimeAsFovealdDoes) {
  const auto name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer) << writer.error().message;
  const TimeNs t0 = monotonic_now_ns() - 5 * kNsPerMs;
  const FoveaFrame sent = moving(t0, 900.0f);
  writer->publish(sent, 1440, 1600);
  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  foveal_fovea f{};
  foveal_motion m{};
  ASSERT_EQ(foveal_client_read(o.c, &f), FOVEAL_OK);
  ASSERT_EQ(foveal_client_motion(o.c, &m), FOVEAL_OK);
  EXPECT_EQ(m.frame, f.frame);
  EXPECT_EQ(m.predictable[0], 1);
  EXPECT_EQ(m.predictable[1], 0);
  EXPECT_FLOAT_EQ(m.velocity_x[0], 900.0f);
  EXPECT_FLOAT_EQ(m.lag_y[0], -1.5f);
  // 0, 21 ms (a display's wait), beyond the 50 ms horizon, and before the sample.
  for (const TimeNs dt : {TimeNs{0}, 21 * kNsPerMs, 80 * kNsPerMs, -10 * kNsPerMs}) {
    foveal_fovea p{};
    ASSERT_EQ(foveal_client_predict(&f, &m, t0 + dt, &p), FOVEAL_OK);
    const FoveaFrame want = predict_fovea(sent, t0 + dt, 1440, 1600);
    for (int e = 0; e < 2; ++e) {
      EXPECT_EQ(p.x[e], want.eyes[e].px.x) << "eye " << e << " at +" << static_cast<double>(dt) / 1e6 << " ms";
      EXPECT_EQ(p.y[e], want.eyes[e].px.y) << "eye " << e << " at +" << static_cast<double>(dt) / 1e6 << " ms";
    }
    EXPECT_EQ(p.t_ns, f.t_ns) << "the time still names the sample";
    EXPECT_EQ(p.state[0], f.state[0]);
  }
  foveal_fovea p{};
  ASSERT_EQ(foveal_client_predict(&f, &m, t0 + 21 * kNsPerMs, &p), FOVEAL_OK);
  EXPECT_NEAR(p.x[0], 700.0f + 4.0f + 900.0f * 0.021f, 1e-3f) << "pursuit: extrapolated with its lag";
  EXPECT_EQ(p.x[1], 300.0f) << "a saccade is held";
  ASSERT_EQ(foveal_client_predict(&f, &m, t0 + 80 * kNsPerMs, &p), FOVEAL_OK);
  EXPECT_NEAR(p.x[0], 700.0f + 4.0f + 900.0f * 0.050f, 1e-3f) << "the horizon stops at 50 ms";
  EXPECT_EQ(FOVEAL_PREDICT_MAX_HORIZON_NS, FoveaPrediction{}.max_horizon_ns) << "the client and foveald use one rule";
  // In place, and clamped inside the viewport.
  m.velocity_x[0] = 1e9f;
  foveal_fovea same = f;
  ASSERT_EQ(foveal_client_predict(&same, &m, t0 + 21 * kNsPerMs, &same), FOVEAL_OK);
  EXPECT_LT(same.x[0], 1440.0f);
  EXPECT_GT(same.x[0], 1439.0f);
}

TEST(FovealClientPredict, AMotionOfAnotherFoveaPredictsNothing) {
  const auto name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer) << writer.error().message;
  const TimeNs t0 = monotonic_now_ns() - 5 * kNsPerMs;
  writer->publish(moving(t0, 900.0f), 1440, 1600);
  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  foveal_fovea f{};
  foveal_motion m{};
  ASSERT_EQ(foveal_client_read(o.c, &f), FOVEAL_OK);
  writer->publish(moving(t0 + kNsPerMs, -900.0f), 1440, 1600);  // foveald published in between
  ASSERT_EQ(foveal_client_motion(o.c, &m), FOVEAL_OK);
  EXPECT_EQ(m.frame, f.frame + 1);
  foveal_fovea p{};
  EXPECT_EQ(foveal_client_predict(&f, &m, t0 + 21 * kNsPerMs, &p), FOVEAL_ERR_NO_DATA);
  EXPECT_EQ(p.x[0], f.x[0]) << "unchanged";
  EXPECT_EQ(foveal_client_predict(nullptr, &m, 0, &p), FOVEAL_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(foveal_client_predict(&f, nullptr, 0, &p), FOVEAL_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(foveal_client_motion(o.c, nullptr), FOVEAL_ERR_INVALID_ARGUMENT);
}

TEST(FovealClientPredict, NothingPublishedYetHasNoMotion) {
  const auto name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer) << writer.error().message;
  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  foveal_motion m{};
  EXPECT_EQ(foveal_client_motion(o.c, &m), FOVEAL_ERR_NO_DATA);
}

TEST(FovealClientPredict, AVersionThreeBlockReadsWithoutMotion) {
  // What a foveald before the motion made: the fovea and the view read, the motion is
  // WRONG_VERSION (predict nothing).
  const auto name = unique_name();
  const int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT, 0600);
  ASSERT_GE(fd, 0);
  ::fchmod(fd, 0600);
  ASSERT_EQ(::ftruncate(fd, FOVEAL_SHM_V3_SIZE), 0);
  unsigned char b[FOVEAL_SHM_V3_SIZE] = {};
  auto put = [&b](std::size_t offset, auto v) { std::memcpy(b + offset, &v, sizeof v); };
  put(FOVEAL_SHM_MAGIC_OFFSET, FOVEAL_SHM_MAGIC);
  put(FOVEAL_SHM_VERSION_OFFSET, 3u);
  put(FOVEAL_SHM_SIZE_OFFSET, static_cast<std::uint32_t>(FOVEAL_SHM_V3_SIZE));
  put(FOVEAL_SHM_HEARTBEAT_OFFSET, monotonic_now_ns());
  put(FOVEAL_SHM_WRITER_STATE_OFFSET, FOVEAL_SHM_WRITER_LIVE);
  put(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, t_ns), monotonic_now_ns());
  put(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, frame), std::uint64_t{3});
  put(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, eye_width), 1440u);
  put(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, eye_height), 1600u);
  ASSERT_EQ(::pwrite(fd, b, sizeof b, 0), static_cast<ssize_t>(sizeof b));
  ::close(fd);
  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  foveal_fovea f{};
  EXPECT_EQ(foveal_client_read(o.c, &f), FOVEAL_OK);
  foveal_motion m{};
  EXPECT_EQ(foveal_client_motion(o.c, &m), FOVEAL_ERR_WRONG_VERSION);
}

TEST(FovealClientPredict, ReadersOnManyThreadsPairOnlyTheirFoveasMotion) {
  // The writer at full speed, readers on two threads: a motion read right after a fovea
  // is that fovea's or a later one's, never an earlier one's (foveald writes it first).
  // Frame i carries velocity i, so a motion under another frame's number shows.
  const auto name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer) << writer.error().message;
  const TimeNs t0 = monotonic_now_ns();
  writer->publish(moving(t0, 1.0f), 1440, 1600);
  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  // The writer publishes until both readers are done: each reads until it has seen many
  // foveas and paired at least one with its motion (a wait for the event, not a count
  // the scheduler could starve).
  std::atomic<int> readers_done{0}, wrong{0}, paired{0};
  std::thread w([&] {
    for (std::uint64_t i = 2; readers_done.load() < 2; ++i) writer->publish(moving(t0, static_cast<float>(i)), 1440, 1600);
  });
  auto reader = [&] {
    int reads = 0, mine = 0;
    while (reads < 2000 || mine == 0) {
      foveal_fovea f{};
      foveal_motion m{};
      if (foveal_client_read(o.c, &f) != FOVEAL_OK || foveal_client_motion(o.c, &m) != FOVEAL_OK) continue;
      ++reads;
      if (m.frame < f.frame) ++wrong;
      if (m.frame == f.frame) {
        ++mine;
        if (m.velocity_x[0] != static_cast<float>(f.frame)) ++wrong;
      }
    }
    paired += mine;
    ++readers_done;
  };
  std::thread r1(reader), r2(reader);
  r1.join();
  r2.join();
  w.join();
  EXPECT_EQ(wrong.load(), 0);
  EXPECT_GT(paired.load(), 0);
}

}  // namespace
}  // namespace foveal
