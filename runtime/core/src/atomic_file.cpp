#include "foveal/core/atomic_file.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <utility>

#include "atomic_file_temps.hpp"
#include "foveal/core/file_mode.hpp"

namespace foveal {

namespace {

/// The mode the temporary file is created with: an existing target's permission bits,
/// else 0666 (the umask then applies, as for any new file). `keep` says whether the
/// bits must be set again after creation (the umask must not narrow them).
Result<mode_t> target_mode(const std::string& path, bool& keep) {
  struct stat st{};
  keep = false;
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return static_cast<mode_t>(0666);
    return io_error(path + ": cannot inspect: " + std::strerror(errno));
  }
  // Renaming over a device, FIFO or link would replace it with a regular file.
  if (!S_ISREG(st.st_mode))
    return bad_input(path + ": is " + file_kind_name(st.st_mode) +
                     (S_ISLNK(st.st_mode) ? "; name the file it points to" : "; outputs go to regular files only"));
  keep = true;
  return static_cast<mode_t>(st.st_mode & 0777);
}

}  // namespace

Result<AtomicFile> AtomicFile::create(const std::string& path) {
  bool keep_mode = false;
  auto mode = target_mode(path, keep_mode);
  if (!mode) return mode.error();
  atomic_temps::remove_stale(path);
  AtomicFile f;
  f.path_ = path;
  // SIGINT and SIGTERM wait while the temporary exists but is not yet registered for
  // removal: delivered in between, they would kill the writer and leave it behind.
  sigset_t cleanup_signals, before;
  sigemptyset(&cleanup_signals);
  sigaddset(&cleanup_signals, SIGINT);
  sigaddset(&cleanup_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &cleanup_signals, &before);
  const int fd = atomic_temps::create_locked(path, keep_mode ? 0600 : *mode, f.tmp_path_);
  const int create_errno = errno;
  if (fd >= 0) f.signal_slot_ = atomic_temps::register_for_signals(f.tmp_path_);
  pthread_sigmask(SIG_SETMASK, &before, nullptr);
  if (fd < 0) return io_error(path + ": cannot create: " + std::strerror(create_errno));
  if (keep_mode) ::fchmod(fd, *mode);  // exactly the old bits, whatever the umask
  f.file_ = ::fdopen(fd, "w");
  if (!f.file_) {
    ::close(fd);
    ::unlink(f.tmp_path_.c_str());
    atomic_temps::unregister_for_signals(std::exchange(f.signal_slot_, -1));
    return io_error(path + ": cannot open stream");
  }
  std::setvbuf(f.file_, nullptr, _IOFBF, 1u << 16);
  return f;
}

AtomicFile::AtomicFile(AtomicFile&& o) noexcept
    : path_(std::move(o.path_)),
      tmp_path_(std::move(o.tmp_path_)),
      file_(std::exchange(o.file_, nullptr)),
      signal_slot_(std::exchange(o.signal_slot_, -1)) {}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    ::unlink(tmp_path_.c_str());
  }
  atomic_temps::unregister_for_signals(signal_slot_);
}

Status AtomicFile::commit() {
  if (!file_) return io_error(path_ + ": already committed");
  const bool write_ok = std::fflush(file_) == 0 && !std::ferror(file_) && ::fsync(::fileno(file_)) == 0;
  const int err = errno;
  Status result;
  bool keep_mode = false;
  if (!write_ok) {
    result = io_error(path_ + ": write failed: " + std::strerror(err));
  } else if (auto mode = target_mode(path_, keep_mode); !mode) {  // it may have changed while we wrote
    result = mode.error();
  } else if (::rename(tmp_path_.c_str(), path_.c_str()) != 0) {
    result = io_error(path_ + ": cannot rename into place: " + std::strerror(errno));
  }
  if (!result) ::unlink(tmp_path_.c_str());
  std::fclose(std::exchange(file_, nullptr));  // after the rename: the lock marks the file live until then
  atomic_temps::unregister_for_signals(std::exchange(signal_slot_, -1));
  return result;
}

Status write_file_atomically(const std::string& path, std::string_view data) {
  auto f = AtomicFile::create(path);
  if (!f) return f.error();
  f->write(data);
  return f->commit();
}

Status check_output_is_not_an_input(const std::string& out, std::initializer_list<std::string_view> inputs) {
  struct stat o{};
  if (::stat(out.c_str(), &o) != 0) return {};  // a new file cannot be an input
  for (std::string_view in : inputs) {
    if (in.empty()) continue;
    const std::string input(in);
    struct stat i{};
    if (::stat(input.c_str(), &i) == 0 && i.st_dev == o.st_dev && i.st_ino == o.st_ino)
      return bad_input(out + ": is the input " + input + "; write the output to another file");
  }
  return {};
}

}  // namespace foveal
