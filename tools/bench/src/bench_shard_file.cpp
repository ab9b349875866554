#include "foveal/bench/bench_shard_file.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>

#include "foveal/core/json_file.hpp"

namespace foveal::bench {

namespace {

const std::vector<Kind>& kinds() {
  // The tables bench_run.cpp, bench_flicker.cpp and bench_gaze.cpp declare.
  static const std::vector<Kind> k = {
      {"bench", "bench.json", "tools/charts/bench_charts.py", {"bench.csv", "fgrid.csv", "rotation.csv", "stability.csv", "flicker.csv"}},
      {"gaze", "gaze.json", "tools/charts/gaze_charts.py", {"gaze.csv", "gaze_frames.csv", "gaze_video.csv", "gaze_video_frames.csv"}},
  };
  return k;
}

// A name from the file, quoted and cut short: messages never print unbounded input.
std::string quoted(const std::string& s) {
  constexpr std::size_t kShown = 60;
  return "'" + (s.size() <= kShown ? s : s.substr(0, kShown) + "...") + "'";
}

}  // namespace

const Kind* find_kind(const std::string& name) {
  for (const Kind& k : kinds())
    if (name == k.name) return &k;
  return nullptr;
}

Result<ShardFile> shard_from_json(const nlohmann::json& j, const std::string& path) {
  ShardFile f;
  f.path = path;
  if (!j.is_object() || !j.contains("format") || j["format"] != kShardFormat)
    return bad_input(f.path + ": field 'format': not a bench shard file");
  if (!j.contains("version") || j["version"] != kShardVersion)
    return bad_input(f.path + ": field 'version': expected " + std::to_string(kShardVersion) + " (written by another foveal version?)");
  if (!j.contains("sweep") || !j["sweep"].is_string()) return bad_input(f.path + ": field 'sweep': expected a string");
  const Kind* kind = j.contains("kind") && j["kind"].is_string() ? find_kind(j["kind"].get<std::string>()) : nullptr;
  if (!kind) {
    std::string known;
    for (const Kind& k : kinds()) known += std::string(known.empty() ? "" : ", ") + k.name;
    return bad_input(f.path + ": field 'kind': expected one of " + known);
  }
  if (!j.contains("summary") || !j["summary"].is_object()) return bad_input(f.path + ": field 'summary': expected an object");
  auto rows = SweepRows::from_json(j.contains("rows") ? j["rows"] : nlohmann::json(), f.path);
  if (!rows) return rows.error();
  for (const std::string& table : rows->tables())
    if (std::find(kind->tables.begin(), kind->tables.end(), table) == kind->tables.end()) {
      std::string known;
      for (const std::string& t : kind->tables) known += (known.empty() ? "" : ", ") + t;
      return bad_input(f.path + ": field 'rows.tables': " + quoted(table) + " is not a table of a '" + kind->name +
                       "' sweep (" + known + ")");
    }
  f.sweep = j["sweep"].get<std::string>();
  f.kind = kind->name;
  f.summary = j["summary"];
  f.rows = std::move(*rows);
  return f;
}

Result<ShardFile> read_shard(const std::string& dir) {
  const std::string path = dir + "/shard.json";
  struct stat st{};
  if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) return bad_input(dir + ": no such directory");
  if (::lstat(path.c_str(), &st) != 0 && errno == ENOENT)
    return bad_input(path + ": missing: not the output of `foveal bench --shard K/N`");
  return read_shard_file(path);
}

Result<ShardFile> read_shard_file(const std::string& path) {
  // Regular files only, size and depth bounded: a FIFO, /dev/zero or a 200,000-deep
  // document is refused before anything recursive sees it.
  auto j = read_json_file(path, "bench shard file", JsonLimits{kMaxShardFileBytes, kMaxJsonDepth});
  if (!j) return j.error();
  return shard_from_json(*j, path);
}

}  // namespace foveal::bench
