#pragma once
// A CSV file the CLI wrote (bench.csv, flicker.csv, frames.csv, ...) as rows keyed by
// the header's column names: plain comma-separated cells, no quoting (the files foveal
// writes have none); an empty last cell is kept.
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace foveal::test {

using CsvRow = std::map<std::string, std::string>;

/// One line's cells, an empty last cell kept.
inline std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream l(line);
  for (std::string c; std::getline(l, c, ',');) cells.push_back(c);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

/// Every line's cells, the header's included.
inline std::vector<std::vector<std::string>> csv_lines(const std::string& text) {
  std::vector<std::vector<std::string>> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(csv_cells(line));
  return lines;
}

inline std::vector<CsvRow> read_csv_rows(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> header;
  std::vector<CsvRow> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = csv_cells(line);
    if (header.empty()) {
      header = cells;
      continue;
    }
    CsvRow r;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) r[header[i]] = cells[i];
    rows.push_back(r);
  }
  return rows;
}

}  // namespace foveal::test
