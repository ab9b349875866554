#include "foveal/tools/run_program.hpp"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

extern char** environ;

namespace foveal::cli {

namespace {

struct Pipe {
  int fd[2] = {-1, -1};
  ~Pipe() {
    for (int f : fd)
      if (f >= 0) ::close(f);
  }
};

}  // namespace

Result<ProgramRun> run_program(const std::vector<std::string>& argv, Capture capture) {
  if (argv.empty()) return Error{ErrorKind::internal, "run_program: no program"};
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  Pipe pipes[2];  // stdout, stderr
  const bool wanted[2] = {capture.out, capture.err};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  for (int i = 0; i < 2; ++i) {
    if (!wanted[i]) continue;
    if (::pipe2(pipes[i].fd, O_CLOEXEC) != 0) {
      posix_spawn_file_actions_destroy(&actions);
      return io_error(argv[0] + ": cannot make a pipe: " + std::strerror(errno));
    }
    posix_spawn_file_actions_adddup2(&actions, pipes[i].fd[1], i == 0 ? STDOUT_FILENO : STDERR_FILENO);  // dup2 clears O_CLOEXEC
  }
  pid_t pid = -1;
  const int rc = ::posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  for (Pipe& p : pipes)
    if (p.fd[1] >= 0) ::close(std::exchange(p.fd[1], -1));  // the child's ends: EOF when it exits
  if (rc != 0) return io_error(argv[0] + ": cannot run: " + std::strerror(rc));
  ProgramRun r;
  std::string* sinks[2] = {&r.out, &r.err};
  // Both pipes at once: a child that fills one while we wait on the other would block.
  while (true) {
    pollfd fds[2];
    nfds_t n = 0;
    int which[2];
    for (int i = 0; i < 2; ++i)
      if (pipes[i].fd[0] >= 0) fds[n] = {pipes[i].fd[0], POLLIN, 0}, which[n++] = i;
    if (n == 0) break;
    if (::poll(fds, n, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (nfds_t k = 0; k < n; ++k) {
      if (!(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      char buf[65536];
      const ssize_t got = ::read(fds[k].fd, buf, sizeof buf);
      if (got > 0) sinks[which[k]]->append(buf, static_cast<std::size_t>(got));
      else if (got == 0 || errno != EINTR) ::close(std::exchange(pipes[which[k]].fd[0], -1));
    }
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return io_error(argv[0] + ": cannot wait for it: " + std::strerror(errno));
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  else if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  return r;
}

std::string describe_end(const ProgramRun& r) {
  if (r.signal) return "killed by signal " + std::to_string(r.signal) + " (" + ::strsignal(r.signal) + ")";
  return "exit status " + std::to_string(r.exit_code);
}

}  // namespace foveal::cli
