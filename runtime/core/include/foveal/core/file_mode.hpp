#pragma once
// Words for what stat() says, for messages that name what is wrong with a path.
#include <sys/stat.h>

#include <cstdio>
#include <string>

namespace foveal {

/// "0755": the permission bits as chmod takes them.
inline std::string mode_text(mode_t m) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%04o", static_cast<unsigned>(m & 07777));
  return buf;
}

/// What a path is ("a FIFO", "a symbolic link"), for "PATH: is a FIFO".
inline const char* file_kind_name(mode_t m) {
  if (S_ISREG(m)) return "a regular file";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISFIFO(m)) return "a FIFO";
  if (S_ISDIR(m)) return "a directory";
  if (S_ISSOCK(m)) return "a socket";
  if (S_ISLNK(m)) return "a symbolic link";
  return "of an unknown kind";
}

}  // namespace foveal
