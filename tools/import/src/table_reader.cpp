#include "foveal/import/table_reader.hpp"

#include <cmath>
#include <unordered_map>

#include "foveal/core/shown_text.hpp"
#include "foveal/core/text_fields.hpp"

namespace foveal {

Result<TableReader> TableReader::open(const std::string& path, char delim) {
  auto lines = LineReader::open(path);
  if (!lines) return lines.error();
  TableReader t(std::move(lines.value()));
  t.delim_ = delim;
  LineReader::Line line;
  auto got = t.lines_.next(line);
  if (!got) return got.error();
  if (!*got || line.text.empty()) return bad_input(path + ":1: file is empty; expected a header row");
  std::string_view head = line.text;
  if (head.substr(0, 3) == "\xEF\xBB\xBF") head.remove_prefix(3);  // UTF-8 BOM
  std::vector<std::string_view> names;
  split_fields(head, delim, names);
  for (auto n : names) t.header_.emplace_back(n);
  t.line_no_ = line.number;
  // A name given twice is ambiguous whichever copy is read (no export repeats one); empty
  // names, from a trailing delimiter, name nothing.
  std::unordered_map<std::string_view, std::size_t> seen;  // a 1 MiB header has up to 512 Ki names
  for (std::size_t i = 0; i < t.header_.size(); ++i) {
    if (t.header_[i].empty()) continue;
    const auto [at, fresh] = seen.emplace(t.header_[i], i);
    if (!fresh)
      return bad_input(path + ":1: column '" + shown_text(t.header_[i]) + "' appears twice in the header (columns " +
                       std::to_string(at->second + 1) + " and " + std::to_string(i + 1) + ")");
  }
  if (t.header_.size() < 2)
    return bad_input(path + ":1: header has " + std::to_string(t.header_.size()) + " column; is the delimiter '" +
                     std::string(1, delim) + "'?");
  return t;
}

Result<std::size_t> TableReader::column(std::string_view name) const {
  const long i = find_column(name);
  if (i < 0) return bad_input(lines_.path() + ":1: column '" + std::string(name) + "' is missing from the header");
  return static_cast<std::size_t>(i);
}

long TableReader::find_column(std::string_view name) const {
  for (std::size_t i = 0; i < header_.size(); ++i)
    if (header_[i] == name) return static_cast<long>(i);
  return -1;
}

Result<bool> TableReader::next() {
  LineReader::Line line;
  for (;;) {
    auto got = lines_.next(line);
    if (!got) return got.error();
    if (!*got) return false;
    line_no_ = line.number;
    if (line.text.empty()) {
      if (blank_line_ == 0) blank_line_ = line.number;  // allowed only at the very end
      continue;
    }
    if (blank_line_ != 0)
      return bad_input(lines_.path() + ":" + std::to_string(blank_line_) + ": blank line inside the data");
    split_fields(line.text, delim_, fields_);
    if (fields_.size() != header_.size()) {
      const std::string what = fields_.size() < header_.size()
                                   ? "missing (row has " + std::to_string(fields_.size()) + " of " +
                                         std::to_string(header_.size()) + " fields" +
                                         (line.terminated ? ")" : "; truncated last row)")
                                   : "row has " + std::to_string(fields_.size()) + " fields, header has " +
                                         std::to_string(header_.size());
      const std::size_t col = std::min(fields_.size(), header_.size() - 1);
      return field_error(col, what);
    }
    return true;
  }
}

Error TableReader::field_error(std::size_t i, const std::string& what) const {
  const std::string col = i < header_.size() ? shown_text(header_[i]) : "#" + std::to_string(i + 1);
  return bad_input(lines_.path() + ":" + std::to_string(line_no_) + ": " + col + ": " + what);
}

template <class T>
Result<T> TableReader::number(std::size_t i) const {
  T v{};
  const std::string_view f = fields_[i];
  if (f.empty()) return field_error(i, "empty");
  if (!parse_number(f, v)) return field_error(i, "'" + shown_text(f) + "' is " + number_problem<T>(f));
  if constexpr (std::is_floating_point_v<T>)
    if (!std::isfinite(v)) return field_error(i, "'" + shown_text(f) + "' is not finite");
  return v;
}

template Result<float> TableReader::number<float>(std::size_t) const;
template Result<double> TableReader::number<double>(std::size_t) const;
template Result<std::int64_t> TableReader::number<std::int64_t>(std::size_t) const;
template Result<std::uint32_t> TableReader::number<std::uint32_t>(std::size_t) const;

}  // namespace foveal
