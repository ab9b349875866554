// foveal-client against the runtime's real writer (FoveaShm) in real shared memory:
// values, settings, and every error a program meets (no writer, wrong version, dead
// writer, someone else's block), each with its message.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "foveal/client.h"
#include "foveal/core/clock.hpp"
#include "foveal/runtime/fovea_shm.hpp"
#include "shm_names.hpp"

namespace foveal {
namespace {

std::string name_prefix() { return "foveal-client-test-" + std::to_string(::getpid()) + "-"; }

/// This test's block name, removed when the test ends, also when it fails.
test::ScopedShmName unique_name() {
  return test::ScopedShmName("/" + name_prefix() + ::testing::UnitTest::GetInstance()->current_test_info()->name());
}

struct ClientTestPrefix {
  std::string operator()() const { return name_prefix(); }
};
[[maybe_unused]] const auto* const g_no_block_left_behind =
    ::testing::AddGlobalTestEnvironment(new test::NoShmLeftBehind<ClientTestPrefix>);

FoveaFrame frame(float lx, float ly, float rx, float ry) {
  FoveaFrame f;
  f.t_ns = 42'000'000'000;
  f.eyes[0] = {{lx, ly}, FoveaState::fixation, 0.9f};
  f.eyes[1] = {{rx, ry}, FoveaState::saccade, 0.5f};
  return f;
}

/// A mapping of the block that the test may write, as a crafted or broken writer would.
struct RawBlock {
  explicit RawBlock(const std::string& block_name, std::size_t bytes = sizeof(FoveaShmBlock), mode_t mode = 0600)
      : name(block_name), size(bytes) {
    const int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT, mode);
    if (fd < 0) return;
    ::fchmod(fd, mode);
    if (::ftruncate(fd, static_cast<off_t>(size)) == 0) {
      void* m = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
      if (m != MAP_FAILED) p = static_cast<unsigned char*>(m);
    }
    ::close(fd);
  }
  ~RawBlock() {
    if (p) ::munmap(p, size);
  }
  template <class T>
  void put(std::size_t offset, T v) {
    std::memcpy(p + offset, &v, sizeof v);
  }
  std::string name;
  unsigned char* p = nullptr;
  std::size_t size = 0;
};

struct Opened {
  foveal_client* c = nullptr;
  foveal_error err{-1, "untouched"};
  explicit Opened(const char* name) { c = foveal_client_open(name, &err); }
  ~Opened() { foveal_client_close(c); }
};

TEST(FovealClient, ReadsTheFoveaAndTheSettingsTheWriterPublished) {
  const auto name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer) << writer.error().message;
  writer->publish_settings({2.25, 3.5, 0.3, -1.0, 0, 0, 7});
  writer->publish(frame(100.5f, 200.25f, 1439.0f, 0.0f), 1440, 1600);

  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  foveal_fovea f{};
  ASSERT_EQ(foveal_client_read(o.c, &f), FOVEAL_OK);
  EXPECT_EQ(f.t_ns, 42'000'000'000);
  EXPECT_EQ(f.eye_width, 1440u);
  EXPECT_EQ(f.eye_height, 1600u);
  EXPECT_FLOAT_EQ(f.x[0], 100.5f);
  EXPECT_FLOAT_EQ(f.y[0], 200.25f);
  EXPECT_FLOAT_EQ(f.x[1], 1439.0f);
  EXPECT_FLOAT_EQ(f.confidence[0], 0.9f);
  EXPECT_EQ(f.state[0], static_cast<std::uint32_t>(FOVEAL_STATE_FIXATION));
  EXPECT_EQ(f.state[1], static_cast<std::uint32_t>(FOVEAL_STATE_SACCADE));
  EXPECT_EQ(f.frame, 1u);

  foveal_settings s{};
  ASSERT_EQ(foveal_client_settings(o.c, &s), FOVEAL_OK);
  EXPECT_DOUBLE_EQ(s.sigma_d, 2.25);
  EXPECT_DOUBLE_EQ(s.sigma_nd, 3.5);
  EXPECT_DOUBLE_EQ(s.f_x, 0.3);
  EXPECT_LT(s.f_y, 0.0);  // automatic
  EXPECT_EQ(s.dominant_eye, 0);
  EXPECT_EQ(s.generation, 7u);

  // A later change reaches the same client.
  writer->publish_settings({2.0, 3.0, 0.3, 0.3, 1, 0, 8});
  ASSERT_EQ(foveal_client_settings(o.c, &s), FOVEAL_OK);
  EXPECT_DOUBLE_EQ(s.sigma_d, 2.0);
  EXPECT_EQ(s.dominant_eye, 1);
  EXPECT_EQ(s.generation, 8u);
}

TEST(FovealClient, NoBlockIsNoWriterAndSaysSo) {
  Opened o(("/foveal-client-missing-" + std::to_string(::getpid())).c_str());
  EXPECT_EQ(o.c, nullptr);
  EXPECT_EQ(o.err.code, FOVEAL_ERR_NO_WRITER);
  EXPECT_NE(std::string(o.err.message).find("is foveald running?"), std::string::npos) << o.err.message;
  EXPECT_NE(std::string(o.err.message).find("/foveal-client-missing-"), std::string::npos) << o.err.message;
}

TEST(FovealClient, NothingPublishedYetIsNoData) {
  const auto name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer);
  writer->publish_settings({2.0, 3.0, 0.3, 0.3, 1, 0, 1});
  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  foveal_fovea f{};
  EXPECT_EQ(foveal_client_read(o.c, &f), FOVEAL_ERR_NO_DATA);
  EXPECT_EQ(f.frame, 0u);
  writer->publish(frame(1, 2, 3, 4), 1440, 1600);
  EXPECT_EQ(foveal_client_read(o.c, &f), FOVEAL_OK);
}

TEST(FovealClient, AStoppedWriterIsNoWriter) {
  const auto name = unique_name();
  std::optional<FoveaShm> writer;
  {
    auto w = FoveaShm::create(name);
    ASSERT_TRUE(w) << w.error().message;
    writer.emplace(std::move(*w));
  }
  writer->publish(frame(1, 2, 3, 4), 1440, 1600);
  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  writer.reset();  // foveald exits: the block's name is gone, this client's mapping stays
  foveal_fovea f{};
  EXPECT_EQ(foveal_client_read(o.c, &f), FOVEAL_ERR_NO_WRITER);
  foveal_settings s{};
  EXPECT_EQ(foveal_client_settings(o.c, &s), FOVEAL_ERR_NO_WRITER);
  EXPECT_NE(std::string(foveal_error_message(FOVEAL_ERR_NO_WRITER)).find("no foveald"), std::string::npos);
}

TEST(FovealClient, ASilentWriterIsDeadAndAWriterThatResumesIsAlive) {
  const auto name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer);
  writer->publish_settings({2.0, 3.0, 0.3, 0.3, 1, 0, 1});
  writer->publish(frame(1, 2, 3, 4), 1440, 1600);
  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;

  RawBlock raw(name);  // a foveald killed 3 s ago: its last heartbeat
  ASSERT_NE(raw.p, nullptr);
  raw.put<std::int64_t>(FOVEAL_SHM_HEARTBEAT_OFFSET, monotonic_now_ns() - 3 * kNsPerSec);
  foveal_fovea f{};
  EXPECT_EQ(foveal_client_read(o.c, &f), FOVEAL_ERR_DEAD_WRITER);
  Opened late(name.c_str());
  EXPECT_EQ(late.c, nullptr);
  EXPECT_EQ(late.err.code, FOVEAL_ERR_DEAD_WRITER);
  EXPECT_NE(std::string(late.err.message).find("pid " + std::to_string(::getpid())), std::string::npos) << late.err.message;

  writer->heartbeat();  // a foveald that was only stalled (or one that took the block over)
  EXPECT_EQ(foveal_client_read(o.c, &f), FOVEAL_OK);
}

TEST(FovealClient, AVersionOneBlockIsWrongVersionNamingIt) {
  const auto name = unique_name();
  {
    RawBlock raw(name, FOVEAL_SHM_V1_SIZE);  // what a foveald before settings made
    ASSERT_NE(raw.p, nullptr);
    raw.put<std::uint32_t>(FOVEAL_SHM_MAGIC_OFFSET, FOVEAL_SHM_MAGIC);
    raw.put<std::uint32_t>(FOVEAL_SHM_VERSION_OFFSET, 1);
    raw.put<std::uint32_t>(FOVEAL_SHM_SIZE_OFFSET, FOVEAL_SHM_V1_SIZE);
  }
  Opened o(name.c_str());
  EXPECT_EQ(o.c, nullptr);
  EXPECT_EQ(o.err.code, FOVEAL_ERR_WRONG_VERSION);
  EXPECT_NE(std::string(o.err.message).find("version-1 block"), std::string::npos) << o.err.message;
  auto runtime_reader = FoveaShm::open(name);  // the runtime's reader refuses it the same way
  ASSERT_FALSE(runtime_reader);
  EXPECT_NE(runtime_reader.error().message.find("version-1 block"), std::string::npos);
}

TEST(FovealClient, ABlockOfAnotherKindIsWrongVersion) {
  const auto name = unique_name();
  {
    RawBlock raw(name, 4096);
    ASSERT_NE(raw.p, nullptr);
    raw.put<std::uint32_t>(0, 0x12345678);
  }
  Opened o(name.c_str());
  EXPECT_EQ(o.c, nullptr);
  EXPECT_EQ(o.err.code, FOVEAL_ERR_WRONG_VERSION);
  EXPECT_NE(std::string(o.err.message).find("not a fovea block"), std::string::npos) << o.err.message;
}

TEST(FovealClient, ALaterVersionWithMoreSectionsStillReads) {
  // Later versions append (fovea_shm_layout.h): this library reads what it knows.
  const auto name = unique_name();
  {
    RawBlock raw(name, 320);
    ASSERT_NE(raw.p, nullptr);
    raw.put<std::uint32_t>(FOVEAL_SHM_MAGIC_OFFSET, FOVEAL_SHM_MAGIC);
    raw.put<std::uint32_t>(FOVEAL_SHM_VERSION_OFFSET, 5);
    raw.put<std::uint32_t>(FOVEAL_SHM_SIZE_OFFSET, 320);
    raw.put<std::int64_t>(FOVEAL_SHM_HEARTBEAT_OFFSET, monotonic_now_ns());
    raw.put<std::uint32_t>(FOVEAL_SHM_WRITER_STATE_OFFSET, FOVEAL_SHM_WRITER_LIVE);
    raw.put<std::int64_t>(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, t_ns), monotonic_now_ns());
    raw.put<std::uint64_t>(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, frame), 5);
    raw.put<std::uint32_t>(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, eye_width), 1440);
    raw.put<std::uint32_t>(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, eye_height), 1600);
    raw.put<float>(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, x), 12.5f);
  }
  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  foveal_fovea f{};
  ASSERT_EQ(foveal_client_read(o.c, &f), FOVEAL_OK);
  EXPECT_EQ(f.frame, 5u);
  EXPECT_FLOAT_EQ(f.x[0], 12.5f);
}

TEST(FovealClient, ABlockOthersMayWriteIsNotFovealds) {
  const auto name = unique_name();
  { RawBlock raw(name, sizeof(FoveaShmBlock), 0666); ASSERT_NE(raw.p, nullptr); }
  Opened o(name.c_str());
  EXPECT_EQ(o.c, nullptr);
  EXPECT_EQ(o.err.code, FOVEAL_ERR_NOT_FOVEALDS);
  EXPECT_NE(std::string(o.err.message).find("mode 0666"), std::string::npos) << o.err.message;
}

TEST(FovealClient, BadArgumentsAreInvalidArgument) {
  Opened bad_name("no-leading-slash");
  EXPECT_EQ(bad_name.c, nullptr);
  EXPECT_EQ(bad_name.err.code, FOVEAL_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(foveal_client_open("/a/b", nullptr), nullptr);  // a null err is allowed
  foveal_fovea f{};
  foveal_settings s{};
  EXPECT_EQ(foveal_client_read(nullptr, &f), FOVEAL_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(foveal_client_settings(nullptr, &s), FOVEAL_ERR_INVALID_ARGUMENT);
  foveal_client_close(nullptr);
  for (int code = FOVEAL_OK; code <= FOVEAL_ERR_SYSTEM + 1; ++code) EXPECT_NE(foveal_error_message(code), nullptr);
}

TEST(FovealClient, TheEnvironmentNamesTheBlockForBothSides) {
  const auto name = unique_name();
  ::setenv("FOVEAL_SHM_NAME", name.c_str(), 1);
  EXPECT_EQ(default_fovea_shm_name(), name);  // foveald's side
  auto writer = FoveaShm::create(default_fovea_shm_name());
  ASSERT_TRUE(writer);
  Opened o(nullptr);
  ::unsetenv("FOVEAL_SHM_NAME");
  EXPECT_NE(o.c, nullptr) << o.err.message;
  EXPECT_EQ(default_fovea_shm_name(), "/foveal-fovea-" + std::to_string(::getuid()));
}

TEST(FovealClient, ReadersOnManyThreadsSeeOnlyWholeValues) {
  // The writer publishes frames whose every field derives from one counter: a torn read
  // would mix two of them. Readers run on several threads on one client (under TSan too).
  const auto name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer);
  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  std::atomic<bool> stop{false}, published{false};
  std::thread w([&] {
    for (int i = 1; !stop.load(); ++i) {
      // Values inside the ranges foveald writes (a 65536-pixel viewport, sigmas in [1, 16], exact in binary).
      const float v = static_cast<float>(i % 60000);
      FoveaFrame f = frame(v, v + 1, v + 2, v + 3);
      f.t_ns = i;
      writer->publish(f, 65536, 65536);
      writer->publish_settings({1.0 + i % 1000 / 128.0, 2.0 + i % 1000 / 128.0, 0.3, 0.3, 1, 0, static_cast<std::uint64_t>(i)});
      writer->heartbeat();
      published = true;
      // Flat out, but with a gap now and then: a writer that never pauses can leave a
      // reader on a loaded 2-core machine overlapping a write on every try (BUSY).
      if (i % 64 == 0) std::this_thread::sleep_for(std::chrono::microseconds(20));
    }
  });
  // The readers start once the writer has published (on a loaded machine they could
  // otherwise finish before its first write and see only NO_DATA).
  while (!published.load()) std::this_thread::yield();
  std::atomic<int> torn{0}, reads{0};
  std::vector<std::thread> readers;
  for (int r = 0; r < 3; ++r)
    readers.emplace_back([&] {
      for (int k = 0; k < 20000; ++k) {
        foveal_fovea f{};
        foveal_settings s{};
        const int rc = foveal_client_read(o.c, &f);
        if (rc == FOVEAL_OK) {
          reads.fetch_add(1);
          const float v = f.x[0];
          if (f.y[0] != v + 1 || f.x[1] != v + 2 || f.y[1] != v + 3 || static_cast<float>(f.t_ns % 60000) != v) torn.fetch_add(1);
        }
        if (foveal_client_settings(o.c, &s) == FOVEAL_OK && s.sigma_nd != s.sigma_d + 1) torn.fetch_add(1);
      }
    });
  for (auto& t : readers) t.join();
  stop = true;
  w.join();
  EXPECT_EQ(torn.load(), 0);
  EXPECT_GT(reads.load(), 0);
}

}  // namespace
}  // namespace foveal

namespace foveal {
namespace {

TEST(FovealClient, TheViewTurnsFoveaPixelsBackIntoTheDirectionsFovealdMapped) {
  const auto name = unique_name();
  auto writer = FoveaShm::create(name);
  ASSERT_TRUE(writer) << writer.error().message;
  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  foveal_view v{};
  EXPECT_EQ(foveal_client_view(o.c, &v), FOVEAL_ERR_NO_DATA);  // not published yet
  DisplayModel m = DisplayModel::vive_pro_eye();
  m.frustum[0] = {-1.3f, 1.1f, -1.4f, 1.2f};  // asymmetric, different per eye
  m.ipd_mm = 61.5f;
  writer->publish_view(m);
  const glm::vec3 left_dir = glm::normalize(glm::vec3{0.2f, -0.1f, -1.0f}), right_dir = glm::normalize(glm::vec3{-0.3f, 0.25f, -1.0f});
  const glm::vec2 lp = m.direction_to_pixel(Eye::left, left_dir), rp = m.direction_to_pixel(Eye::right, right_dir);
  writer->publish(frame(lp.x, lp.y, rp.x, rp.y), m.eye_width, m.eye_height);
  ASSERT_EQ(foveal_client_view(o.c, &v), FOVEAL_OK);
  EXPECT_FLOAT_EQ(v.tan_left[0], -1.3f);
  EXPECT_FLOAT_EQ(v.tan_top[1], m.frustum[1].tan_top);
  EXPECT_FLOAT_EQ(v.ipd_m, 0.0615f);
  foveal_fovea f{};
  ASSERT_EQ(foveal_client_read(o.c, &f), FOVEAL_OK);
  float d[3];
  ASSERT_EQ(foveal_view_direction(&v, &f, 0, d), FOVEAL_OK);
  EXPECT_NEAR(glm::dot(glm::vec3(d[0], d[1], d[2]), left_dir), 1.0f, 1e-6f);
  ASSERT_EQ(foveal_view_direction(&v, &f, 1, d), FOVEAL_OK);
  EXPECT_NEAR(glm::dot(glm::vec3(d[0], d[1], d[2]), right_dir), 1.0f, 1e-6f);
  EXPECT_EQ(foveal_view_direction(&v, &f, 2, d), FOVEAL_ERR_INVALID_ARGUMENT);
  f.x[0] = std::nanf("");
  EXPECT_EQ(foveal_view_direction(&v, &f, 0, d), FOVEAL_ERR_INVALID_ARGUMENT);
}

TEST(FovealClient, AVersionTwoBlockReadsButHasNoView) {
  const auto name = unique_name();
  {
    RawBlock raw(name, FOVEAL_SHM_V2_SIZE);  // what a foveald before the view made
    ASSERT_NE(raw.p, nullptr);
    raw.put<std::uint32_t>(FOVEAL_SHM_MAGIC_OFFSET, FOVEAL_SHM_MAGIC);
    raw.put<std::uint32_t>(FOVEAL_SHM_VERSION_OFFSET, 2);
    raw.put<std::uint32_t>(FOVEAL_SHM_SIZE_OFFSET, FOVEAL_SHM_V2_SIZE);
    raw.put<std::int64_t>(FOVEAL_SHM_HEARTBEAT_OFFSET, monotonic_now_ns());
    raw.put<std::uint32_t>(FOVEAL_SHM_WRITER_STATE_OFFSET, FOVEAL_SHM_WRITER_LIVE);
    raw.put<std::int64_t>(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, t_ns), monotonic_now_ns());
    raw.put<std::uint64_t>(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, frame), 3);
    raw.put<std::uint32_t>(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, eye_width), 1440);
    raw.put<std::uint32_t>(FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, eye_height), 1600);
  }
  Opened o(name.c_str());
  ASSERT_NE(o.c, nullptr) << o.err.message;
  foveal_fovea f{};
  EXPECT_EQ(foveal_client_read(o.c, &f), FOVEAL_OK);
  foveal_view v{};
  EXPECT_EQ(foveal_client_view(o.c, &v), FOVEAL_ERR_WRONG_VERSION);
}

}  // namespace
}  // namespace foveal
