#include <gtest/gtest.h>
#include <fcntl.h>

#include <sys/mman.h>
#include <unistd.h>

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
