#include "foveal/bench/bench_sweep.hpp"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <cstdlib>
#include <map>

#include "foveal/bench/shard_cells.hpp"
#include "foveal/core/shown_text.hpp"

namespace foveal::bench {

namespace {

// After the rows of the same and earlier points: a point's rows keep the order they were
// added in, and a run that adds rows out of point order still stores them in it.
template <class Rows, class Row>
void insert_in_point_order(Rows& rows, Row row) {
  const auto at = std::upper_bound(rows.begin(), rows.end(), row.point, [](std::size_t p, const auto& r) { return p < r.point; });
  rows.insert(at, std::move(row));
}

}  // namespace

Result<Shard> parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  auto integer = [](const std::string& s, int& v) {
    char* end = nullptr;
    const long n = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end || n < 1 || n > kMaxShards) return false;
    v = static_cast<int>(n);
    return true;
  };
  Shard s;
  if (slash == std::string::npos || !integer(text.substr(0, slash), s.k) || !integer(text.substr(slash + 1), s.n) || s.k > s.n)
    return bad_input("--shard: expected K/N with 1 <= K <= N (e.g. 3/8), got '" + text + "'");
  return s;
}

bool SweepRows::mine(std::size_t point) const {
  return static_cast<int>(point % static_cast<std::size_t>(shard_.n)) == shard_.k - 1;
}

bool SweepRows::take() {
  running_ = mine(next_++);
  return running_;
}

bool SweepRows::take(std::size_t* point) {
  *point = next_;
  return take();
}

std::size_t SweepRows::current() const {
  assert(running_ && next_ > 0 && "rows belong to a point this shard took");
  return next_ - 1;
}

// Each point's rows come from one shard in their own order: a stable sort by point
// gives the single run's order.
void SweepRows::sort() {
  auto by_point = [](const auto& a, const auto& b) { return a.point < b.point; };
  for (auto& [file, t] : tables_) std::stable_sort(t.lines.begin(), t.lines.end(), by_point);
  for (auto& [name, items] : lists_) std::stable_sort(items.begin(), items.end(), by_point);
}

void SweepRows::table(const std::string& file, const std::string& header) { tables_[file].header = header; }

void SweepRows::add_line(const std::string& file, std::string line) {
  assert(tables_.count(file) && "declare the table first");
  insert_in_point_order(tables_[file].lines, Tagged<std::string>{current(), std::move(line)});
}

void SweepRows::add_item(const std::string& list, nlohmann::json item) {
  insert_in_point_order(lists_[list], Tagged<nlohmann::json>{current(), std::move(item)});
}

void SweepRows::add_line(const std::string& file, std::string line, std::size_t point) {
  assert(tables_.count(file) && point < next_ && mine(point) && "a point this shard took");
  insert_in_point_order(tables_[file].lines, Tagged<std::string>{point, std::move(line)});
}

void SweepRows::add_item(const std::string& list, nlohmann::json item, std::size_t point) {
  assert(point < next_ && mine(point) && "a point this shard took");
  insert_in_point_order(lists_[list], Tagged<nlohmann::json>{point, std::move(item)});
}

std::vector<std::string> SweepRows::tables() const {
  std::vector<std::string> out;
  for (const auto& [file, t] : tables_) out.push_back(file);
  return out;
}

std::size_t SweepRows::lines(const std::string& file) const {
  const auto it = tables_.find(file);
  return it == tables_.end() ? 0 : it->second.lines.size();
}

std::string SweepRows::csv(const std::string& file) const {
  const auto it = tables_.find(file);
  if (it == tables_.end()) return "";
  std::string out = it->second.header + "\n";
  for (const auto& l : it->second.lines) out += l.value + "\n";
  return out;
}

nlohmann::json SweepRows::list(const std::string& name) const {
  nlohmann::json out = nlohmann::json::array();
  if (const auto it = lists_.find(name); it != lists_.end())
    for (const auto& item : it->second) out.push_back(item.value);
  return out;
}

nlohmann::json SweepRows::to_json() const {
  nlohmann::json tables = nlohmann::json::object(), lists = nlohmann::json::object();
  for (const auto& [file, t] : tables_) {
    nlohmann::json lines = nlohmann::json::array();
    for (const auto& l : t.lines) lines.push_back({l.point, l.value});
    tables[file] = {{"header", t.header}, {"lines", lines}};
  }
  for (const auto& [name, items] : lists_) {
    nlohmann::json arr = nlohmann::json::array();
    for (const auto& i : items) arr.push_back({i.point, i.value});
    lists[name] = arr;
  }
  return {{"shard", {shard_.k, shard_.n}}, {"points", next_}, {"tables", tables}, {"lists", lists}};
}

Result<SweepRows> SweepRows::from_json(const nlohmann::json& j, const std::string& where) {
  auto bad = [&](const std::string& what) { return bad_input(where + ": " + what); };
  if (!j.is_object() || !j.contains("shard") || !j["shard"].is_array() || j["shard"].size() != 2 ||
      !j["shard"][0].is_number_integer() || !j["shard"][1].is_number_integer())
    return bad("field 'shard': expected [K, N]");
  // Range-checked as int64 first: a cast of 1e10 to int would be garbage. N is bounded
  // like --shard's, and merge needs all N directories, so a huge N is never a real sweep.
  const auto k = j["shard"][0].get<std::int64_t>(), n = j["shard"][1].get<std::int64_t>();
  if (n < 1 || n > kMaxShards) return bad("field 'shard': N must lie in 1.." + std::to_string(kMaxShards));
  if (k < 1 || k > n) return bad("field 'shard': K must lie in 1..N");
  SweepRows r(Shard{static_cast<int>(k), static_cast<int>(n)});
  if (!j.contains("points") || !j["points"].is_number_unsigned()) return bad("field 'points': expected a count");
  r.next_ = j["points"].get<std::size_t>();
  // A row must come from a point of this shard: anything else is a damaged or edited file.
  auto point_of = [&](const nlohmann::json& row, const std::string& field) -> Result<std::size_t> {
    if (!row.is_array() || row.size() != 2 || !row[0].is_number_unsigned())
      return bad("field '" + field + "': expected [point, row] pairs");
    const auto p = row[0].get<std::size_t>();
    if (p >= r.next_ || static_cast<int>(p % static_cast<std::size_t>(r.shard_.n)) != r.shard_.k - 1)
      return bad("field '" + field + "': point " + std::to_string(p) + " is not one of shard " + r.shard_.text() + "'s");
    return p;
  };
  if (!j.contains("tables") || !j["tables"].is_object()) return bad("field 'tables': expected an object");
  for (const auto& [file, t] : j["tables"].items()) {
    const std::string field = "tables." + file;
    if (!t.is_object() || !t.contains("header") || !t["header"].is_string() || !t.contains("lines") || !t["lines"].is_array())
      return bad("field '" + field + "': expected {header, lines}");
    Table& table = r.tables_[file];
    table.header = t["header"].get<std::string>();
    // Rows are copied into the merged CSV verbatim: each must be one plain row.
    const std::string at = where + ": " + shown_text(file, 40);
    if (Status s = check_csv_line(table.header, "", at + " header"); !s) return s.error();
    std::size_t line = 1;  // the header is line 1 of the shard's own table file
    for (const auto& l : t["lines"]) {
      auto p = point_of(l, field + ".lines");
      if (!p) return p.error();
      if (!l[1].is_string()) return bad("field '" + field + ".lines': a line must be a string");
      const std::string& text = l[1].get_ref<const std::string&>();
      if (Status s = check_csv_line(text, table.header, at + " line " + std::to_string(++line)); !s) return s.error();
      table.lines.push_back({*p, text});
    }
  }
  if (!j.contains("lists") || !j["lists"].is_object()) return bad("field 'lists': expected an object");
  for (const auto& [name, items] : j["lists"].items()) {
    if (!items.is_array()) return bad("field 'lists." + name + "': expected an array");
    auto& list = r.lists_[name];
    for (const auto& i : items) {
      auto p = point_of(i, "lists." + name);
      if (!p) return p.error();
      list.push_back({*p, i[1]});
    }
  }
  return r;
}

Result<SweepRows> SweepRows::merge(const std::vector<SweepRows>& parts, const std::vector<std::string>& names) {
  if (parts.empty()) return bad_input("merge: no shards given");
  const SweepRows& first = parts.front();
  const int n = first.shard_.n;
  std::map<int, std::size_t> seen;  // shard K -> its part: memory for the parts given, not for N
  SweepRows out;
  out.next_ = first.next_;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const SweepRows& p = parts[i];
    if (p.shard_.n != n)
      return bad_input(names[i] + ": shard " + p.shard_.text() + " of a sweep in " + std::to_string(p.shard_.n) + " parts, but " +
                       names[0] + " is one of " + std::to_string(n));
    if (const auto [at, added] = seen.emplace(p.shard_.k, i); !added)
      return bad_input(names[i] + ": shard " + p.shard_.text() + " is given twice (also " + names[at->second] + ")");
    if (p.next_ != first.next_)
      return bad_input(names[i] + ": a sweep of " + std::to_string(p.next_) + " points, but " + names[0] + "'s has " +
                       std::to_string(first.next_));
    if (p.tables() != first.tables())
      return bad_input(names[i] + ": writes other tables than " + names[0] + " (not the same sweep)");
    for (const auto& [file, t] : p.tables_) {
      Table& merged = out.tables_[file];
      if (i > 0 && merged.header != t.header)
        return bad_input(names[i] + ": " + file + " has another header than in " + names[0]);
      merged.header = t.header;
      merged.lines.insert(merged.lines.end(), t.lines.begin(), t.lines.end());
    }
    for (const auto& [name, items] : p.lists_) {
      auto& merged = out.lists_[name];
      merged.insert(merged.end(), items.begin(), items.end());
    }
  }
  if (seen.size() != static_cast<std::size_t>(n)) {
    // The first few missing shards by name, then a count: N may be a million.
    constexpr std::size_t kNamed = 10;
    std::string missing;
    std::size_t named = 0;
    for (int k = 1; k <= n && named < kNamed; ++k)
      if (!seen.count(k)) missing += (named++ ? ", " : "") + std::to_string(k) + "/" + std::to_string(n);
    const std::size_t absent = static_cast<std::size_t>(n) - seen.size();
    if (absent > named) missing += " and " + std::to_string(absent - named) + " more";
    return bad_input("merge: shard " + missing + " missing (every one of the " + std::to_string(n) + " is needed)");
  }
  out.sort();
  return out;
}

}  // namespace foveal::bench
