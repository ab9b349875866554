#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "foveal/runtime/seqlock.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

// Every field equals the same counter: a torn read shows up as unequal fields.
struct Payload {
  std::uint64_t a, b, c;
  double d;
  std::uint32_t e;
};

TEST(SeqLock, StoreThenLoad) {
  SeqLock<Payload> s;
  Payload p{};
  ASSERT_TRUE(s.load(p));
  EXPECT_EQ(p.a, 0u);
  s.store({1, 2, 3, 4.5, 6});
  ASSERT_TRUE(s.load(p));
  EXPECT_EQ(p.a, 1u);
  EXPECT_EQ(p.c, 3u);
  EXPECT_DOUBLE_EQ(p.d, 4.5);
  EXPECT_EQ(p.e, 6u);
  EXPECT_EQ(s.version(), 2u);  // the constructor's store and ours
}

TEST(SeqLock, ReadersNeverSeeATornValue) {
  SeqLock<Payload> s;
  std::atomic<bool> done{false};
  std::atomic<std::uint64_t> reads{0}, torn{0}, went_back{0};
  std::vector<std::thread> readers;
  for (int r = 0; r < 2; ++r)
    readers.emplace_back([&] {
      std::uint64_t last = 0;
      Payload p{};
      while (!done.load(std::memory_order_relaxed)) {
        if (!s.load(p)) continue;
        ++reads;
        if (p.a != p.b || p.b != p.c || p.d != static_cast<double>(p.a) || p.e != static_cast<std::uint32_t>(p.a)) ++torn;
        if (p.a < last) ++went_back;
        last = p.a;
      }
    });
  // Let the readers get going first: on a loaded machine they may start late.
  EXPECT_TRUE(test::eventually([&] { return reads.load() >= 100; }, test::kEventWithinMs, 1));  // joined below either way
  constexpr std::uint64_t kWrites = 200000;
  for (std::uint64_t k = 1; k <= kWrites; ++k)
    s.store({k, k, k, static_cast<double>(k), static_cast<std::uint32_t>(k)});
  done = true;
  for (auto& t : readers) t.join();
  EXPECT_GT(reads.load(), 0u);
  EXPECT_EQ(torn.load(), 0u);
  EXPECT_EQ(went_back.load(), 0u);
  Payload p{};
  ASSERT_TRUE(s.load(p));
  EXPECT_EQ(p.a, kWrites);
}

}  // namespace
}  // namespace foveal
