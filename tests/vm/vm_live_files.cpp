#include "vm_live_files.hpp"

#include <fstream>
#include <sstream>

namespace foveal::vmtest {

using nlohmann::json;

namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, ',')) out.push_back(f);
  return out;
}

/// Calls `row` with the fields of every data row of a CSV file that has at least `fields`.
template <class Row>
void for_each_row(const std::string& path, std::size_t fields, Row row) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);  // header
  while (std::getline(f, line))
    if (const auto v = split_csv(line); v.size() >= fields) row(v);
}

}  // namespace

std::vector<TraceRow> read_trace(const std::string& path) {
  std::vector<TraceRow> rows;
  for_each_row(path, 9, [&](const std::vector<std::string>& v) {
    TraceRow r;
    r.rel = std::stoll(v[0]);
    for (std::size_t e = 0; e < 2; ++e) {
      r.state[e] = v[1 + 4 * e];
      r.x[e] = std::stod(v[2 + 4 * e]);
      r.y[e] = std::stod(v[3 + 4 * e]);
    }
    rows.push_back(std::move(r));
  });
  return rows;
}

std::vector<FrameRow> read_frames(const std::string& path) {
  std::vector<FrameRow> rows;
  for_each_row(path, 7, [&](const std::vector<std::string>& v) {
    FrameRow r;
    r.t_ns = std::stoll(v[1]);
    for (std::size_t e = 0; e < 2; ++e) {
      r.fx[e] = std::stod(v[3 + 2 * e]);
      r.fy[e] = std::stod(v[4 + 2 * e]);
    }
    rows.push_back(r);
  });
  return rows;
}

json read_json(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return json::parse(ss.str(), nullptr, false);
}

json at(const json& j, const std::string& pointer) {
  const json::json_pointer p(pointer);
  return j.is_object() && j.contains(p) ? j.at(p) : json();
}

std::string str_at(const json& j, const std::string& pointer) {
  const json v = at(j, pointer);
  return v.is_string() ? v.get<std::string>() : "";
}

std::uint64_t u64_at(const json& j, const std::string& pointer) {
  const json v = at(j, pointer);
  return v.is_number_unsigned() ? v.get<std::uint64_t>() : 0;
}

}  // namespace foveal::vmtest
