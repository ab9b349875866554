#include "foveal/tools/staged_outputs.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <utility>

#include "foveal/core/file_mode.hpp"

namespace foveal::cli {

namespace {

constexpr const char* kPrefix = ".foveal-staging.";

// Removes staging directories of `dir` that a killed process left: this user's, older
// than 2 s (the instant between mkdtemp and flock) and not locked by a live one.
void remove_stale(const std::string& dir) {
  DIR* d = ::opendir(dir.c_str());
  if (!d) return;
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    if (name.rfind(kPrefix, 0) != 0) continue;
    const std::string path = dir + "/" + name;
    struct stat st{};
    if (::lstat(path.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::geteuid() ||
        std::time(nullptr) - st.st_mtime < 2)
      continue;
    const int fd = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
    ::close(fd);
  }
  ::closedir(d);
}

bool plain_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos && name.find('\0') == std::string::npos;
}

}  // namespace

std::string describe_write_error(int err) {
  if (err == ENOSPC) return std::string(std::strerror(err)) + " (ENOSPC: the disk is full)";
  if (err == EDQUOT) return std::string(std::strerror(err)) + " (EDQUOT: over the disk quota)";
  return std::strerror(err);
}

Result<StagedOutputs> StagedOutputs::create(const std::string& dir) {
  StagedOutputs s;
  s.dir_ = dir;
  std::error_code ec;
  s.created_dir_ = std::filesystem::create_directories(dir, ec);
  if (ec) return io_error(dir + ": cannot create directory: " + ec.message());
  remove_stale(dir);
  std::string tmpl = dir + "/" + kPrefix + "XXXXXX";
  if (!::mkdtemp(tmpl.data())) {
    const int err = errno;
    s.discard();
    return io_error(dir + ": cannot create a staging directory: " + describe_write_error(err));
  }
  s.staging_ = tmpl;
  s.lock_fd_ = ::open(s.staging_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (s.lock_fd_ >= 0) ::flock(s.lock_fd_, LOCK_EX);
  return s;
}

StagedOutputs::StagedOutputs(StagedOutputs&& o) noexcept
    : dir_(std::move(o.dir_)),
      staging_(std::exchange(o.staging_, std::string())),
      lock_fd_(std::exchange(o.lock_fd_, -1)),
      created_dir_(std::exchange(o.created_dir_, false)) {}

StagedOutputs::~StagedOutputs() { discard(); }

void StagedOutputs::discard() {
  std::error_code ec;
  if (!staging_.empty()) std::filesystem::remove_all(std::exchange(staging_, std::string()), ec);
  if (lock_fd_ >= 0) ::close(std::exchange(lock_fd_, -1));
  if (std::exchange(created_dir_, false)) ::rmdir(dir_.c_str());  // only when empty
}

Status StagedOutputs::write(const std::string& name, std::string_view data) {
  if (!plain_name(name)) return Error{ErrorKind::internal, dir_ + ": output name '" + name + "' is not a plain file name"};
  const std::string path = staging_ + "/" + name, shown = dir_ + "/" + name;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) return io_error(shown + ": cannot create: " + describe_write_error(errno));
  std::size_t done = 0;
  int err = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      err = n < 0 ? errno : EIO;
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  if (!err && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && !err) err = errno;
  if (err) return io_error(shown + ": write failed: " + describe_write_error(err));
  return {};
}

Result<std::vector<std::string>> StagedOutputs::commit() {
  if (staging_.empty()) return io_error(dir_ + ": outputs already committed");
  std::vector<std::string> names;
  if (DIR* d = ::opendir(staging_.c_str())) {
    while (const dirent* e = ::readdir(d)) {
      struct stat st{};
      const std::string name = e->d_name;
      if (plain_name(name) && ::lstat((staging_ + "/" + name).c_str(), &st) == 0 && S_ISREG(st.st_mode)) names.push_back(name);
    }
    ::closedir(d);
  } else {
    return io_error(staging_ + ": cannot list: " + std::strerror(errno));
  }
  // Every target first, so that a refused one stops the set before anything moved.
  for (const std::string& name : names) {
    const std::string target = dir_ + "/" + name;
    struct stat st{};
    if (::lstat(target.c_str(), &st) != 0) {
      if (errno != ENOENT) return io_error(target + ": cannot inspect: " + std::strerror(errno));
      continue;
    }
    if (!S_ISREG(st.st_mode))
      return bad_input(target + ": is " + file_kind_name(st.st_mode) +
                       (S_ISLNK(st.st_mode) ? "; name the file it points to" : "; outputs go to regular files only"));
    ::chmod((staging_ + "/" + name).c_str(), st.st_mode & 0777);  // an existing file keeps its mode
  }
  for (const std::string& name : names)
    if (::rename((staging_ + "/" + name).c_str(), (dir_ + "/" + name).c_str()) != 0)
      return io_error(dir_ + "/" + name + ": cannot rename into place: " + std::strerror(errno));
  created_dir_ = false;  // it holds the outputs now
  discard();
  return names;
}

}  // namespace foveal::cli
