#include "foveal/quality/quality_targets.hpp"

#include <array>
#include <cmath>
#include <string_view>

#include "foveal/core/line_reader.hpp"
#include "foveal/core/text_fields.hpp"

namespace foveal {

namespace {

constexpr std::array<std::string_view, 4> kColumns = {"start_s", "end_s", "azimuth_deg", "elevation_deg"};

}  // namespace

Result<std::vector<QualityTarget>> read_quality_targets(const std::string& path) {
  auto lines = LineReader::open(path);
  if (!lines) return lines.error();
  LineReader::Line line;
  std::vector<std::string_view> fields;
  std::vector<std::string> header;
  std::array<std::size_t, kColumns.size()> index{};
  std::vector<QualityTarget> targets;
  auto where = [&](std::uint64_t n) { return path + ":" + std::to_string(n); };
  for (;;) {
    auto got = lines->next(line);
    if (!got) return got.error();
    if (!*got) break;
    std::string_view text = line.text;
    if (text.empty() || text.front() == '#') continue;  // blank lines and comments
    split_fields(text, ',', fields);
    if (header.empty()) {
      for (std::string_view f : fields) header.emplace_back(f);
      for (std::size_t c = 0; c < kColumns.size(); ++c) {
        std::size_t i = 0;
        while (i < header.size() && header[i] != kColumns[c]) ++i;
        if (i == header.size())
          return bad_input(where(line.number) + ": column '" + std::string(kColumns[c]) +
                           "' is missing from the header (expected start_s,end_s,azimuth_deg,elevation_deg)");
        index[c] = i;
      }
      continue;
    }
    if (fields.size() != header.size())
      return bad_input(where(line.number) + ": row has " + std::to_string(fields.size()) + " fields, header has " +
                       std::to_string(header.size()));
    std::array<double, kColumns.size()> v{};
    for (std::size_t c = 0; c < kColumns.size(); ++c) {
      const std::string_view f = fields[index[c]];
      if (!parse_number(f, v[c]) || !std::isfinite(v[c]))
        return bad_input(where(line.number) + ": " + std::string(kColumns[c]) + ": '" + std::string(f) +
                         "' is not a finite number");
    }
    QualityTarget t{v[0], v[1], {v[2], v[3]}, where(line.number)};
    if (t.end_s <= t.start_s) return bad_input(t.where + ": end_s: must be greater than start_s");
    if (std::fabs(t.at.azimuth_deg) >= 90) return bad_input(t.where + ": azimuth_deg: must lie in (-90, 90)");
    if (std::fabs(t.at.elevation_deg) >= 90) return bad_input(t.where + ": elevation_deg: must lie in (-90, 90)");
    targets.push_back(std::move(t));
  }
  if (header.empty()) return bad_input(path + ": file is empty; expected the header start_s,end_s,azimuth_deg,elevation_deg");
  if (targets.empty()) return bad_input(path + ": no targets: the file has a header only");
  return targets;
}

}  // namespace foveal
