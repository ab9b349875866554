#include "atomic_file_temps.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <limits.h>
#include <sys/file.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <iterator>

#include "foveal/core/atomic_file.hpp"

namespace foveal::atomic_temps {

namespace {

/// A temporary file unlocked for this long was left by a dead writer.
constexpr time_t kStaleAfterS = 2;

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";

std::string random_suffix() {
  unsigned char bytes[kSuffixLength];
  if (::getrandom(bytes, sizeof bytes, 0) != static_cast<ssize_t>(sizeof bytes))
    for (unsigned char& b : bytes) b = static_cast<unsigned char>(std::rand());  // no entropy: still unique by O_EXCL
  std::string s;
  for (unsigned char b : bytes) s += kAlphabet[b % (sizeof kAlphabet - 1)];
  return s;
}

std::string dir_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string base_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

bool is_temp_name_of(const char* name, const std::string& prefix) {
  if (std::strncmp(name, prefix.c_str(), prefix.size()) != 0) return false;
  const char* suffix = name + prefix.size();
  if (std::strlen(suffix) != kSuffixLength) return false;
  for (const char* c = suffix; *c; ++c)
    if (!std::strchr(kAlphabet, *c)) return false;
  return true;
}

// The signal handler only reads these: fixed storage, no allocation.
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 holds a name
  char path[PATH_MAX];
};
Slot g_slots[16];

}  // namespace

int create_locked(const std::string& target, unsigned mode, std::string& tmp_path) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    tmp_path = target + ".tmp." + random_suffix();
    const int fd = ::open(tmp_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode);
    if (fd < 0 && errno == EEXIST) continue;
    if (fd >= 0) (void)::flock(fd, LOCK_EX | LOCK_NB);  // a fresh name: nobody else holds it
    return fd;
  }
  errno = EEXIST;
  return -1;
}

void remove_stale(const std::string& target) {
  const std::string dir = dir_of(target), prefix = base_of(target) + ".tmp.";
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd < 0) return;
  DIR* d = ::fdopendir(dfd);
  if (!d) {
    ::close(dfd);
    return;
  }
  const time_t now = std::time(nullptr);
  while (const dirent* e = ::readdir(d)) {
    if (!is_temp_name_of(e->d_name, prefix)) continue;
    const int fd = ::openat(dfd, e->d_name, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) continue;
    struct stat st{};
    // Only our own regular files, only old ones, only when no writer holds the lock.
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_uid == ::geteuid() &&
        now - st.st_mtime >= kStaleAfterS && ::flock(fd, LOCK_EX | LOCK_NB) == 0) {
      struct stat named{};
      if (::fstatat(dfd, e->d_name, &named, AT_SYMLINK_NOFOLLOW) == 0 && named.st_ino == st.st_ino &&
          named.st_dev == st.st_dev)
        ::unlinkat(dfd, e->d_name, 0);
    }
    ::close(fd);
  }
  ::closedir(d);
}

int register_for_signals(const std::string& tmp_path) {
  if (tmp_path.size() >= PATH_MAX) return -1;
  for (int i = 0; i < static_cast<int>(std::size(g_slots)); ++i) {
    int expected = 0;
    if (!g_slots[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(g_slots[i].path, tmp_path.c_str(), tmp_path.size() + 1);
    g_slots[i].state.store(2);
    return i;
  }
  return -1;
}

void unregister_for_signals(int slot) {
  if (slot >= 0) g_slots[slot].state.store(0);
}

namespace {

void remove_temporaries_and_die(int sig) {
  for (Slot& s : g_slots)
    if (s.state.load() == 2) ::unlink(s.path);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

}  // namespace foveal::atomic_temps

namespace foveal {

void remove_temporary_files_on_signals() {
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction old{};
    if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;  // ignored or handled: leave it
    struct sigaction sa{};
    sa.sa_handler = atomic_temps::remove_temporaries_and_die;
    sigemptyset(&sa.sa_mask);
    ::sigaction(sig, &sa, nullptr);
  }
}

}  // namespace foveal
