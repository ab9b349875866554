#pragma once
// The kinds of bench output and a shard's file (shard.json): what `foveal bench --shard`
// writes and `foveal bench merge` reads. A library of its own (foveal::bench_shard) so
// that the fuzz target fuzz_shard reads shard.json exactly as merge does.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/bench/bench_sweep.hpp"
#include "foveal/core/error.hpp"

namespace foveal::bench {

/// What a sweep of one kind writes: its JSON file, chart script (under the data
/// directory) and the only table files it may write. A shard naming any other table is
/// refused: table names become file names in the output directory.
struct Kind {
  const char* name;
  const char* json_file;
  const char* charts;
  std::vector<std::string> tables;
};
const Kind* find_kind(const std::string& name);

/// Largest shard.json read (the biggest committed bench.json is 80 KB).
inline constexpr std::size_t kMaxShardFileBytes = std::size_t{64} << 20;

struct ShardFile {
  std::string path;  ///< DIR/shard.json
  std::string sweep, kind;
  nlohmann::json summary;
  SweepRows rows;
};
/// Reads DIR/shard.json: a regular file within kMaxShardFileBytes and JSON's depth
/// limit (foveal/core/json_file.hpp), of a known kind, naming only its kind's tables.
Result<ShardFile> read_shard(const std::string& dir);
/// The same for the file itself (what fuzz_shard feeds).
Result<ShardFile> read_shard_file(const std::string& path);
/// The same checks on a parsed document; `path` names it in messages.
Result<ShardFile> shard_from_json(const nlohmann::json& j, const std::string& path);

/// shard.json's "format" and "version".
inline constexpr const char* kShardFormat = "foveal bench shard";
inline constexpr int kShardVersion = 1;

}  // namespace foveal::bench
