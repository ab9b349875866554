#pragma once
// Writes a file so that readers see either the old file or the complete new one:
// data goes to a temporary file in the same directory, renamed over the target on
// commit(). Destroying an uncommitted AtomicFile removes the temporary file.
#include <cstdio>
#include <string>
#include <string_view>

#include "foveal/core/error.hpp"

namespace foveal {

class AtomicFile {
 public:
  static Result<AtomicFile> create(const std::string& path);
  AtomicFile(AtomicFile&&) noexcept;
  AtomicFile& operator=(AtomicFile&&) = delete;
  AtomicFile(const AtomicFile&) = delete;
  ~AtomicFile();

  /// Buffered write; errors surface at commit().
  void write(std::string_view data) { std::fwrite(data.data(), 1, data.size(), file_); }
  std::FILE* stream() { return file_; }
  /// Flushes, fsyncs and renames onto the target path.
  Status commit();
  const std::string& path() const { return path_; }

 private:
  AtomicFile() = default;
  std::string path_, tmp_path_;
  std::FILE* file_ = nullptr;
};

/// Convenience: writes `data` to `path` atomically.
Status write_file_atomically(const std::string& path, std::string_view data);

}  // namespace foveal
