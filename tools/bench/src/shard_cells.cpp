#include "foveal/bench/shard_cells.hpp"

#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "foveal/core/shown_text.hpp"

namespace foveal::bench {

namespace {

std::vector<std::string_view> cells(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

// A number as the bench writes them (and strtod reads them): digits, a sign, an exponent,
// inf and nan included.
bool is_number(std::string_view cell) {
  if (cell.empty() || cell.size() > 64) return false;
  const std::string s(cell);
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

std::string control_name(unsigned char c) {
  char buf[48];
  const char* name = c == 0 ? ", NUL" : c == '\n' ? ", a newline" : c == '\r' ? ", a carriage return" : c == 0x1b ? ", ESC" : c == '\t' ? ", a tab" : "";
  std::snprintf(buf, sizeof buf, "0x%02x%s", c, name);
  return buf;
}

}  // namespace

Status check_csv_line(const std::string& line, const std::string& columns, const std::string& where) {
  const std::vector<std::string_view> names = columns.empty() ? std::vector<std::string_view>{} : cells(columns);
  const std::vector<std::string_view> row = cells(line);
  for (std::size_t i = 0; i < row.size(); ++i) {
    const std::string column = "column " + std::to_string(i + 1) +
                               (i < names.size() ? " '" + shown_text(names[i], 40) + "'" : std::string());
    for (const char ch : row[i]) {
      const auto c = static_cast<unsigned char>(ch);
      if (c < 0x20 || c == 0x7f)
        return bad_input(where + ", " + column + ": a control character (" + control_name(c) +
                         ") in the cell; a shard's tables hold plain text, one row per line");
    }
    const char first = row[i].empty() ? '\0' : row[i].front();
    if ((first == '=' || first == '+' || first == '-' || first == '@') && !is_number(row[i]))
      return bad_input(where + ", " + column + ": the text cell starts with '" + std::string(1, first) +
                       "', which a spreadsheet would run as a formula; bench writes no such cell");
  }
  return {};
}

}  // namespace foveal::bench
