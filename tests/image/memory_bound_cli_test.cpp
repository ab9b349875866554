// Issue 38, item 9: commands whose memory grows with their input size it from headers and
// options before any work (refused past FOVEAL_MEMORY_LIMIT_GB, exit 2), and an
// allocation that fails anyway ends the command with exit 1 and a message, not an abort.
// The JOD cases are in tests/perception/jod_cli_test.cpp.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "foveal/image/image.hpp"
#include "sanitizers.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

// foveal with a guard that only ends a hang or a runaway: every case exits at once.
std::string guarded(const std::string& args) { return "timeout -s KILL 120 " + test::bin("foveal") + " " + args; }

TEST(ImageProbe, ReadsTheHeaderOnlyAndRefusesWhatLoadRefuses) {
  test::TempDir d;
  image::Image img(40, 30);
  ASSERT_TRUE(image::save_png(d.path("a.png"), img));
  auto h = image::probe(d.path("a.png"));
  ASSERT_TRUE(h) << h.error().message;
  EXPECT_EQ(h->width, 40);
  EXPECT_EQ(h->height, 30);
  EXPECT_EQ(h->file_bytes, std::filesystem::file_size(d.path("a.png")));
  ASSERT_EQ(::mkfifo(d.path("f.png").c_str(), 0600), 0);
  auto fifo = image::probe(d.path("f.png"));  // would block in open(2) if it waited for a writer
  ASSERT_FALSE(fifo);
  EXPECT_NE(fifo.error().message.find("is a FIFO"), std::string::npos) << fifo.error().message;
  test::write_file(d.path("t.png"), "not an image");
  EXPECT_FALSE(image::probe(d.path("t.png")));
}

// `render --size 16384x16384` was accepted and aborted on bad_alloc at 5.2 GB: the frame's
// memory is estimated from its size before a GL context exists (so no GL is needed here).
TEST(RenderMemory, ASizePastTheBoundIsRefusedBeforeAnyWork) {
  test::TempDir d;
  auto r = test::run(guarded("render --size 16384x16384 --out " + d.path("x.png")) + " </dev/null");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  // The default bound: 8 GB, or half the machine's memory.
  EXPECT_NE(r.err.find("render --size: needs about 8.9 GB for a 16384x16384 frame; the bound is "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("FOVEAL_MEMORY_LIMIT_GB=10 raises it"), std::string::npos) << r.err;
  auto low = test::run("env FOVEAL_MEMORY_LIMIT_GB=0.5 " + guarded("render --size 4096x4096 --out " + d.path("x.png")));
  EXPECT_EQ(low.exit_code, 2) << low.err;
  EXPECT_NE(low.err.find("needs about 837 MB for a 4096x4096 frame; the bound is 500 MB (FOVEAL_MEMORY_LIMIT_GB=1 raises it)"),
            std::string::npos)
      << low.err;
  EXPECT_FALSE(std::filesystem::exists(d.path("x.png")));
}

// Under an address-space cap below what the work needs (the estimate let through with a
// raised bound), the allocation fails: exit 1 naming the command and "out of memory",
// wherever it failed (the JOD's worker threads included). Not under sanitizers: they
// reserve terabytes of shadow address space, so RLIMIT_AS cannot be used.
TEST(OutOfMemory, AFailedAllocationEndsTheCommandWithExitOneNotAnAbort) {
#ifdef FOVEAL_TEST_SANITIZED
  GTEST_SKIP() << "RLIMIT_AS caps are meaningless under ASan/TSan (shadow memory)";
#endif
  test::TempDir d;
  image::Image a(4096, 4096), b(4096, 4096);
  for (std::size_t i = 0; i < a.rgba.size(); ++i) a.rgba[i] = 100, b.rgba[i] = (i % 4 == 0) ? 90 : 100;
  ASSERT_TRUE(image::save_png(d.path("a.png"), a));
  ASSERT_TRUE(image::save_png(d.path("b.png"), b));
  // JOD of two 4096² stills needs ~0.7 GB (decoding them ~0.3): a 600 MB cap fails in scoring.
  auto r = test::run("env FOVEAL_MEMORY_LIMIT_GB=100 prlimit --as=600000000 " +
                     guarded("metrics --jod --ref " + d.path("a.png") + " --test " + d.path("b.png")));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("foveal: error: foveal metrics: out of memory (an allocation failed)"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

}  // namespace
}  // namespace foveal
