#pragma once
// Streams a text file line by line through a fixed buffer: memory stays flat whatever
// the file's size. Used by the gaze-log reader and the importers.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "foveal/core/error.hpp"

namespace foveal {

class LineReader {
 public:
  struct Line {
    std::string_view text;     ///< without the line end ('\n', and '\r' if crlf); the
                               ///< 8 bytes after text.end() are readable (word-wise parsing)
    std::uint64_t number = 0;  ///< 1-based
    bool crlf = false;         ///< the line ended in "\r\n"
    bool terminated = true;    ///< false for a last line with no line end
  };

  static Result<LineReader> open(const std::string& path);
  LineReader(LineReader&&) noexcept;
  LineReader& operator=(LineReader&&) noexcept;
  ~LineReader();

  /// Next line; false at end of file. An I/O error or an over-long line (> 1 MiB) is
  /// returned as an error naming the file and line.
  Result<bool> next(Line& out);
  /// Back to the first byte of the file (line numbers restart).
  Status rewind();
  const std::string& path() const { return path_; }
  std::uint64_t bytes_read() const { return bytes_read_; }

 private:
  LineReader() = default;
  Status refill();

  std::string path_;
  int fd_ = -1;
  std::unique_ptr<char[]> buf_;
  std::size_t begin_ = 0, end_ = 0;
  bool eof_ = false;
  std::uint64_t line_no_ = 0;
  std::uint64_t bytes_read_ = 0;
};

}  // namespace foveal
