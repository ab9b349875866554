#pragma once
// Writes a file so that readers see either the old file or the complete new one:
// data goes to a temporary file `PATH.tmp.XXXXXX` in the same directory, renamed over
// the target on commit(). Destroying an uncommitted AtomicFile removes the temporary file.
//
// The target must be absent or a regular file: a device, FIFO, directory, socket or
// symbolic link at the path is refused (bad_input, naming it) rather than replaced. A new
// file gets mode 0666 less the umask; an existing file keeps its permission bits.
// Temporary files of the same target left by a killed writer are removed first
// (docs/bad-input.md, "Files, sockets and shared memory").
#include <cstdio>
#include <initializer_list>
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
  int signal_slot_ = -1;  ///< where the temporary name is registered for SIGINT/SIGTERM
};

/// Convenience: writes `data` to `path` atomically.
Status write_file_atomically(const std::string& path, std::string_view data);

/// bad_input naming both paths when `out` exists and is the same file (st_dev, st_ino)
/// as one of `inputs`: a command that read the input would otherwise replace it.
/// Empty strings in `inputs` are skipped.
Status check_output_is_not_an_input(const std::string& out, std::initializer_list<std::string_view> inputs);

/// Installs SIGINT and SIGTERM handlers (where the disposition is still the default)
/// that remove the temporary files of every uncommitted AtomicFile, then die of the
/// signal as before. For the command-line tools; a program with its own handlers
/// (foveald) stops cleanly instead and its AtomicFiles clean up as they are destroyed.
void remove_temporary_files_on_signals();

}  // namespace foveal
