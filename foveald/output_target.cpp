#include "output_target.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "foveal/core/file_mode.hpp"

namespace foveal::daemon {

Status check_output_target(const std::string& path) {
  struct stat st{};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return {};
    return io_error(path + ": cannot inspect: " + std::strerror(errno));
  }
  if (S_ISREG(st.st_mode)) return {};
  return bad_input(path + ": is " + file_kind_name(st.st_mode) +
                   (S_ISLNK(st.st_mode) ? "; name the file it points to" : "; outputs go to regular files only"));
}

}  // namespace foveal::daemon
