#include "foveal/core/line_reader.hpp"

#include "foveal/core/read_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace foveal {

namespace {
constexpr std::size_t kBufSize = 1u << 20;  // also the longest line accepted
constexpr std::size_t kPadding = 8;         // readable bytes after any line (see header)
}

Result<LineReader> LineReader::open(const std::string& path) {
  LineReader r;
  r.path_ = path;
  auto fd = open_regular_file(path, "input");  // a FIFO without a writer must not block us
  if (!fd) return fd.error();
  r.fd_ = *fd;
  r.buf_ = std::make_unique<char[]>(kBufSize + kPadding);  // value-initialised: padding is 0
#ifdef POSIX_FADV_SEQUENTIAL
  ::posix_fadvise(r.fd_, 0, 0, POSIX_FADV_SEQUENTIAL);
#endif
  return r;
}

LineReader::LineReader(LineReader&& o) noexcept { *this = std::move(o); }

LineReader& LineReader::operator=(LineReader&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(o.path_);
    fd_ = std::exchange(o.fd_, -1);
    buf_ = std::move(o.buf_);
    begin_ = o.begin_;
    end_ = o.end_;
    eof_ = o.eof_;
    line_no_ = o.line_no_;
    bytes_read_ = o.bytes_read_;
  }
  return *this;
}

LineReader::~LineReader() {
  if (fd_ >= 0) ::close(fd_);
}

Status LineReader::refill() {
  // Move the unconsumed tail to the front, then fill the rest.
  if (begin_ > 0) {
    std::memmove(buf_.get(), buf_.get() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  while (end_ < kBufSize && !eof_) {
    const ssize_t n = ::read(fd_, buf_.get() + end_, kBufSize - end_);
    if (n < 0) {
      if (errno == EINTR) continue;
      return io_error(path_ + ": read failed: " + std::strerror(errno));
    }
    if (n == 0) eof_ = true;
    end_ += static_cast<std::size_t>(n);
    bytes_read_ += static_cast<std::uint64_t>(n);
    if (n > 0) break;  // one read per refill keeps latency low on big buffers
  }
  return {};
}

Result<bool> LineReader::next(Line& out) {
  for (;;) {
    const char* start = buf_.get() + begin_;
    const std::size_t avail = end_ - begin_;
    const void* nl = avail ? std::memchr(start, '\n', avail) : nullptr;
    if (nl) {
      const std::size_t len = static_cast<std::size_t>(static_cast<const char*>(nl) - start);
      out.number = ++line_no_;
      out.terminated = true;
      out.crlf = len > 0 && start[len - 1] == '\r';
      out.text = std::string_view(start, out.crlf ? len - 1 : len);
      begin_ += len + 1;
      return true;
    }
    if (eof_) {
      if (avail == 0) return false;
      out.number = ++line_no_;
      out.terminated = false;
      out.crlf = false;
      out.text = std::string_view(start, avail);
      begin_ = end_;
      return true;
    }
    if (begin_ == 0 && end_ == kBufSize)
      return bad_input(path_ + ":" + std::to_string(line_no_ + 1) + ": line longer than 1 MiB");
    if (Status s = refill(); !s) return s.error();
  }
}

Status LineReader::rewind() {
  if (::lseek(fd_, 0, SEEK_SET) < 0) return io_error(path_ + ": cannot seek: " + std::strerror(errno));
  begin_ = end_ = 0;
  eof_ = false;
  line_no_ = 0;
  return {};
}

}  // namespace foveal
