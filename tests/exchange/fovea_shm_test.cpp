#include <gtest/gtest.h>
#include <fcntl.h>

#include <sys/mman.h>
#include <unistd.h>

#include <atomic>
#include <cstddef>
#include <cstring>
#include <thread>

#include "foveal/runtime/fovea_shm.hpp"

namespace foveal {
namespace {

std::string unique_name() { return "/foveal-test-" + std::to_string(::getpid()) + "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name(); }

TEST(FoveaShm, AReaderSeesWhatTheWriterPublished) {
  const std::string name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer) << writer.error().message;
  auto reader = FoveaShm::open(name);  // a second mapping, as another process would have
  ASSERT_TRUE(reader) << reader.error().message;
  FoveaFrame f;
  f.t_ns = 123456789;
  f.eyes[0] = {{100.5f, 200.25f}, FoveaState::fixation, 0.9f};
  f.eyes[1] = {{1439.0f, 0.0f}, FoveaState::blink, 0.0f};
  writer->publish(f, 1440, 1600);
  FoveaShmPayload p{};
  ASSERT_TRUE(reader->read(p));
  EXPECT_EQ(p.t_ns, 123456789);
  EXPECT_EQ(p.eye_width, 1440u);
  EXPECT_EQ(p.eye_height, 1600u);
  EXPECT_FLOAT_EQ(p.x[0], 100.5f);
  EXPECT_FLOAT_EQ(p.y[0], 200.25f);
  EXPECT_FLOAT_EQ(p.x[1], 1439.0f);
  EXPECT_EQ(p.state[1], static_cast<std::uint32_t>(FoveaState::blink));
  EXPECT_EQ(p.frame, 1u);
}

TEST(FoveaShm, SettingsAndLivenessReachReaders) {
  const std::string name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer) << writer.error().message;
  auto reader = FoveaShm::open(name);
  ASSERT_TRUE(reader) << reader.error().message;
  FoveaShmSettings s{};
  ASSERT_TRUE(reader->read_settings(s));
  EXPECT_EQ(s.generation, 0u) << "nothing published yet";
  writer->publish_settings({2.2, 3.1, 0.25, -1.0, 0, 0, 4});
  ASSERT_TRUE(reader->read_settings(s));
  EXPECT_DOUBLE_EQ(s.sigma_d, 2.2);
  EXPECT_DOUBLE_EQ(s.sigma_nd, 3.1);
  EXPECT_EQ(s.dominant_eye, 0u);
  EXPECT_EQ(s.generation, 4u);
  // The header and the liveness words, at the offsets docs/fovea-shm.md gives.
  const int fd = ::shm_open(name.c_str(), O_RDONLY, 0);
  ASSERT_GE(fd, 0);
  unsigned char raw[FOVEAL_SHM_V2_SIZE];
  ASSERT_EQ(::pread(fd, raw, sizeof raw, 0), static_cast<ssize_t>(sizeof raw));
  ::close(fd);
  std::uint32_t version = 0, size = 0, pid = 0, state = 0;
  std::memcpy(&version, raw + FOVEAL_SHM_VERSION_OFFSET, 4);
  std::memcpy(&size, raw + FOVEAL_SHM_SIZE_OFFSET, 4);
  std::memcpy(&pid, raw + FOVEAL_SHM_WRITER_PID_OFFSET, 4);
  std::memcpy(&state, raw + FOVEAL_SHM_WRITER_STATE_OFFSET, 4);
  EXPECT_EQ(version, 4u);
  EXPECT_EQ(size, 256u);
  EXPECT_EQ(pid, static_cast<std::uint32_t>(::getpid()));
  EXPECT_EQ(state, FOVEAL_SHM_WRITER_LIVE);
}

TEST(FoveaShm, TheMotionOfEachFoveaReachesReadersPairedByItsFrame) {
  // Version 4: what predict_fovea needs beyond the fovea, at the offsets docs/fovea-shm.md gives.
  const std::string name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer) << writer.error().message;
  auto reader = FoveaShm::open(name);
  ASSERT_TRUE(reader) << reader.error().message;
  FoveaShmMotion m{};
  ASSERT_TRUE(reader->read_motion(m));
  EXPECT_EQ(m.frame, 0u) << "nothing published yet";
  FoveaFrame f;
  f.t_ns = 5'000'000'000;
  f.eyes[0].px = {700.0f, 800.0f};
  f.eyes[0].state = FoveaState::pursuit;
  f.eyes[0].velocity_px_s = {250.5f, -40.25f};
  f.eyes[0].lag_px = {3.5f, -0.5f};
  f.eyes[0].predictable = true;
  f.eyes[1].state = FoveaState::saccade;  // held: not predictable, no velocity
  writer->publish(f, 1440, 1600);
  f.eyes[0].velocity_px_s = {1.0f, 2.0f};
  writer->publish(f, 1440, 1600);
  FoveaShmPayload p{};
  ASSERT_TRUE(reader->read(p));
  ASSERT_TRUE(reader->read_motion(m));
  EXPECT_EQ(m.frame, p.frame) << "the motion names the fovea it belongs to";
  EXPECT_EQ(m.frame, 2u);
  EXPECT_FLOAT_EQ(m.velocity_x[0], 1.0f);
  EXPECT_FLOAT_EQ(m.velocity_y[0], 2.0f);
  EXPECT_FLOAT_EQ(m.lag_x[0], 3.5f);
  EXPECT_FLOAT_EQ(m.lag_y[0], -0.5f);
  EXPECT_EQ(m.predictable[0], 1u);
  EXPECT_EQ(m.predictable[1], 0u);
  // The raw words, as a C reader sees them.
  const int fd = ::shm_open(name.c_str(), O_RDONLY, 0);
  ASSERT_GE(fd, 0);
  unsigned char raw[FOVEAL_SHM_V4_SIZE];
  ASSERT_EQ(::pread(fd, raw, sizeof raw, 0), static_cast<ssize_t>(sizeof raw));
  ::close(fd);
  std::uint64_t frame = 0;
  float lag_x0 = 0;
  std::memcpy(&frame, raw + FOVEAL_SHM_MOTION_WORDS_OFFSET + offsetof(foveal_shm_motion, frame), 8);
  std::memcpy(&lag_x0, raw + FOVEAL_SHM_MOTION_WORDS_OFFSET + offsetof(foveal_shm_motion, lag_x), 4);
  EXPECT_EQ(frame, 2u);
  EXPECT_FLOAT_EQ(lag_x0, 3.5f);
}

TEST(FoveaShm, AReaderNeverPairsAFoveaWithAnOlderMotion) {
  // The writer puts the motion down before its fovea: a reader that reads the fovea and
  // then the motion sees the same frame or a later one, never an earlier one.
  const std::string name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer) << writer.error().message;
  auto reader = FoveaShm::open(name);
  ASSERT_TRUE(reader) << reader.error().message;
  // The writer publishes until the reader has read many foveas and paired one with its
  // motion: a wait for the event, not a count the scheduler could starve.
  std::atomic<bool> done{false};
  std::thread w([&] {
    FoveaFrame f;
    f.t_ns = 1;
    for (std::uint64_t i = 1; !done.load(); ++i) {
      f.eyes[0].velocity_px_s.x = static_cast<float>(i);  // the frame it will carry
      writer->publish(f, 64, 64);
    }
  });
  int reads = 0, paired = 0, wrong = 0;
  while (reads < 2000 || paired == 0) {
    FoveaShmPayload p{};
    FoveaShmMotion m{};
    if (!reader->read(p) || !reader->read_motion(m) || p.frame == 0) continue;
    ++reads;
    if (m.frame < p.frame) ++wrong;
    if (m.frame == p.frame) {
      ++paired;
      if (m.velocity_x[0] != static_cast<float>(p.frame)) ++wrong;  // a motion under another frame's number
    }
  }
  done = true;
  w.join();
  EXPECT_EQ(wrong, 0);
}

TEST(FoveaShm, OpeningWithoutADaemonIsAClearError) {
  auto r = FoveaShm::open("/foveal-test-missing-" + std::to_string(::getpid()));
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("is foveald running"), std::string::npos) << r.error().message;
}

TEST(FoveaShm, ABlockOfAnotherLayoutIsRefused) {
  const std::string name = unique_name();
  const int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT, 0600);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::ftruncate(fd, 4096), 0);  // zeros: wrong magic
  ::close(fd);
  auto r = FoveaShm::open(name);
  EXPECT_FALSE(r);
  ::shm_unlink(name.c_str());
}

TEST(FoveaShm, TheWriterRemovesTheBlockWhenDone) {
  const std::string name = unique_name();
  { auto w = FoveaShm::create(name); ASSERT_TRUE(w); }
  EXPECT_FALSE(FoveaShm::open(name));
}

}  // namespace
}  // namespace foveal
