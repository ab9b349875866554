// The layer's log inside an app whose stderr nobody reads (issue 38 item 4): a line that
// does not fit is dropped and counted, never waited on, and a reader that is gone raises
// no SIGPIPE in the app.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>

#include "layer_log.hpp"
#include "test_support.hpp"

namespace foveal::openxr {
namespace {

/// Runs `body` in a child with stderr on `fd`; its exit status, or -1 if it is still
/// running after the guard (a hang).
int in_child_with_stderr(int fd, void (*body)()) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(fd, STDERR_FILENO);
    body();
    std::_Exit(0);
  }
  return test::wait_for_exit(pid, 30000);
}

TEST(LayerLog, AFullPipeNobodyReadsDropsLinesInsteadOfBlocking) {
  int p[2];
  ASSERT_EQ(::pipe(p), 0);
  // Fill the pipe, as a launcher's unread stderr is after a while.
  const int flags = ::fcntl(p[1], F_GETFL);
  ::fcntl(p[1], F_SETFL, flags | O_NONBLOCK);
  char chunk[4096] = {};
  while (::write(p[1], chunk, sizeof chunk) > 0) {}
  ::fcntl(p[1], F_SETFL, flags);  // the app's descriptor blocks, as a launcher leaves it
  const int rc = in_child_with_stderr(p[1], [] {
    for (int i = 0; i < 100; ++i) log_line("foveald stopped: eye gaze inactive until it is back");
    std::_Exit(log_lines_dropped() == 100 ? 0 : 3);
  });
  EXPECT_EQ(rc, 0) << "-1: the child hung on a write to its full stderr; 3: lines were not counted as dropped";
  // The app's own descriptor keeps its blocking mode: the layer wrote through its own.
  EXPECT_FALSE(::fcntl(p[1], F_GETFL) & O_NONBLOCK);
  ::close(p[0]);
  ::close(p[1]);
}

TEST(LayerLog, AReaderThatIsGoneRaisesNoSigpipeInTheApp) {
  int p[2];
  ASSERT_EQ(::pipe(p), 0);
  ::close(p[0]);
  const int rc = in_child_with_stderr(p[1], [] {
    ::signal(SIGPIPE, SIG_DFL);  // an app that never asked for SIGPIPE to be ignored
    log_line("no gaze from foveald yet");
    std::_Exit(log_lines_dropped() == 1 ? 0 : 3);
  });
  EXPECT_EQ(rc, 0) << "128 + 13: the app died of SIGPIPE";
  ::close(p[1]);
}

TEST(LayerLog, LinesReachAReadableStderrWhole) {
  test::TempDir dir;
  const std::string path = dir.path("err.txt");
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  ASSERT_GE(fd, 0);
  const int rc = in_child_with_stderr(fd, [] {
    log_line("one");
    if (::write(STDERR_FILENO, "app\n", 4) != 4) std::_Exit(4);  // the app's own line after the layer's
    log_line("two");
    std::_Exit(log_lines_dropped() == 0 ? 0 : 3);
  });
  ::close(fd);
  EXPECT_EQ(rc, 0);
  EXPECT_EQ(test::read_file(path), "foveal-openxr: one\napp\nfoveal-openxr: two\n");
}

}  // namespace
}  // namespace foveal::openxr
