#pragma once
// Reads third-party delimited tables (SRanipal, Pupil Labs) by column name. Tolerant of
// what real exports contain (UTF-8 BOM, CRLF, blank lines at the end), strict about
// everything else; errors name file:line: column.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/core/line_reader.hpp"

namespace foveal {

class TableReader {
 public:
  static Result<TableReader> open(const std::string& path, char delim);

  /// Index of a required column; error names the file and the column.
  Result<std::size_t> column(std::string_view name) const;
  /// Index of an optional column, or -1.
  long find_column(std::string_view name) const;

  /// Next data row; false at the end. Rows with a different field count than the
  /// header are errors (a truncated last row included).
  Result<bool> next();
  std::string_view field(std::size_t i) const { return fields_[i]; }
  const std::vector<std::string>& header() const { return header_; }
  std::uint64_t line() const { return line_no_; }
  const std::string& path() const { return lines_.path(); }

  /// Parses field i as T. Empty, partial, non-numeric and (for floats) NaN/Inf fields
  /// are errors naming the file, line and column.
  template <class T>
  Result<T> number(std::size_t i) const;
  Error field_error(std::size_t i, const std::string& what) const;

 private:
  explicit TableReader(LineReader lines) : lines_(std::move(lines)) {}
  LineReader lines_;
  char delim_ = ',';
  std::vector<std::string> header_;
  std::vector<std::string_view> fields_;
  std::uint64_t line_no_ = 0, blank_line_ = 0;
};

}  // namespace foveal
