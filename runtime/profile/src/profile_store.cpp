#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cstdlib>
#include <filesystem>

#include "foveal/core/atomic_file.hpp"
#include "foveal/core/clock.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/core/read_file.hpp"
#include "foveal/runtime/profile.hpp"

namespace foveal {

namespace fs = std::filesystem;

ProfileStore ProfileStore::user() {
  if (const char* x = std::getenv("XDG_CONFIG_HOME"); x && *x) return ProfileStore(std::string(x) + "/foveal");
  const char* home = std::getenv("HOME");
  return ProfileStore(std::string(home && *home ? home : ".") + "/.config/foveal");
}

Result<std::vector<std::string>> ProfileStore::list() const {
  std::vector<std::string> names;
  std::error_code ec;
  const fs::path dir = root_ + "/profiles";
  if (!fs::exists(dir, ec)) return names;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const fs::path& p = entry.path();
    if (p.extension() == ".json" && valid_profile_name(p.stem().string())) names.push_back(p.stem().string());
  }
  if (ec) return io_error(dir.string() + ": cannot list: " + ec.message());
  std::sort(names.begin(), names.end());
  return names;
}

bool ProfileStore::exists(const std::string& name) const {
  std::error_code ec;
  return valid_profile_name(name) && fs::is_regular_file(path_of(name), ec);
}

Result<Profile> ProfileStore::load_file(const std::string& path, const std::string& name) {
  auto j = read_json_file(path, "profile");
  if (!j) return j.error();
  return Profile::from_json(*j, name, path);
}

Result<Profile> ProfileStore::load(const std::string& name) const {
  if (!valid_profile_name(name)) return bad_input("profile name '" + name + "': use letters, digits, '-' and '_'");
  if (!exists(name)) return bad_input("profile '" + name + "' does not exist (" + path_of(name) + ")");
  return load_file(path_of(name), name);
}

Status ProfileStore::save(const Profile& p) const {
  if (!valid_profile_name(p.name)) return bad_input("profile name '" + p.name + "': use letters, digits, '-' and '_'");
  if (Status s = p.validate("profile " + p.name); !s) return s;
  std::error_code ec;
  fs::create_directories(root_ + "/profiles", ec);
  if (ec) return io_error(root_ + "/profiles: cannot create: " + ec.message());
  return write_file_atomically(path_of(p.name), json_text(p.to_json(), 2) + "\n");
}

Status ProfileStore::remove(const std::string& name) const {
  if (!exists(name)) return bad_input("profile '" + name + "' does not exist");
  std::error_code ec;
  fs::remove(path_of(name), ec);
  if (ec) return io_error(path_of(name) + ": cannot remove: " + ec.message());
  return {};
}

Result<std::string> ProfileStore::active() const {
  // A regular file only, opened without blocking: a FIFO here hung every reader (and
  // foveald with its signals masked), a device would be read without end.
  const std::string path = root_ + "/active";
  if (::access(path.c_str(), F_OK) != 0 && errno == ENOENT) return std::string("default");
  auto text = read_regular_file(path, 4096, "the active-profile file");
  if (!text) return text.error();
  const std::string name = text->substr(0, text->find('\n'));
  return valid_profile_name(name) ? name : std::string("default");
}

Status ProfileStore::set_active(const std::string& name) const {
  if (!exists(name)) return bad_input("profile '" + name + "' does not exist");
  return write_file_atomically(root_ + "/active", name + "\n");
}

ProfileStore::Lock::~Lock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the flock
}

Result<ProfileStore::Lock> ProfileStore::lock(int timeout_ms) const {
  std::error_code ec;
  fs::create_directories(root_, ec);
  if (ec) return io_error(root_ + ": cannot create: " + ec.message());
  const std::string path = root_ + "/lock";
  // O_NONBLOCK: a FIFO planted here must not hold the open; only a regular file is a lock.
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK, 0600);
  if (fd < 0) return io_error(path + ": cannot open the profile store's lock file: " + std::strerror(errno));
  Lock held(fd);
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
    return bad_input(path + ": the profile store's lock file is not a regular file; remove it");
  const TimeNs deadline = monotonic_now_ns() + static_cast<TimeNs>(timeout_ms) * kNsPerMs;
  while (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno != EWOULDBLOCK && errno != EINTR) return io_error(path + ": cannot lock: " + std::strerror(errno));
    if (monotonic_now_ns() >= deadline)
      return io_error(path + ": another foveal command has held the profile store's lock for " +
                      std::to_string(timeout_ms / 1000) + " s; try again");
    sleep_until_ns(monotonic_now_ns() + kNsPerMs);
  }
  return held;
}

}  // namespace foveal
