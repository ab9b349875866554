#include "foveal/core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <vector>

namespace foveal {

Result<AtomicFile> AtomicFile::create(const std::string& path) {
  AtomicFile f;
  f.path_ = path;
  std::string tmpl = path + ".tmp.XXXXXX";
  std::vector<char> buf(tmpl.begin(), tmpl.end());
  buf.push_back('\0');
  const int fd = ::mkstemp(buf.data());
  if (fd < 0) return io_error(path + ": cannot create: " + std::strerror(errno));
  ::fchmod(fd, 0644);  // mkstemp makes 0600; outputs are ordinary files
  f.tmp_path_ = buf.data();
  f.file_ = ::fdopen(fd, "w");
  if (!f.file_) {
    ::close(fd);
    ::unlink(f.tmp_path_.c_str());
    return io_error(path + ": cannot open stream");
  }
  std::setvbuf(f.file_, nullptr, _IOFBF, 1u << 16);
  return f;
}

AtomicFile::AtomicFile(AtomicFile&& o) noexcept
    : path_(std::move(o.path_)), tmp_path_(std::move(o.tmp_path_)), file_(std::exchange(o.file_, nullptr)) {}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    ::unlink(tmp_path_.c_str());
  }
}

Status AtomicFile::commit() {
  if (!file_) return io_error(path_ + ": already committed");
  const bool write_ok = std::fflush(file_) == 0 && !std::ferror(file_) && ::fsync(::fileno(file_)) == 0;
  const int err = errno;
  std::fclose(std::exchange(file_, nullptr));
  if (!write_ok) {
    ::unlink(tmp_path_.c_str());
    return io_error(path_ + ": write failed: " + std::strerror(err));
  }
  if (::rename(tmp_path_.c_str(), path_.c_str()) != 0) {
    const int e = errno;
    ::unlink(tmp_path_.c_str());
    return io_error(path_ + ": cannot rename into place: " + std::strerror(e));
  }
  return {};
}

Status write_file_atomically(const std::string& path, std::string_view data) {
  auto f = AtomicFile::create(path);
  if (!f) return f.error();
  f->write(data);
  return f->commit();
}

}  // namespace foveal
