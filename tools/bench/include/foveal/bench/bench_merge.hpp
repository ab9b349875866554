#pragma once
// foveal bench merge: joins the shards of one sweep (each the output of
// `foveal bench --shard K/N`) into the files a single run of the whole sweep writes, from
// the same rows in the same order (docs/bench.md, "On a cluster").
#include <string>
#include <vector>

namespace foveal::bench {

struct MergeOptions {
  std::string out;                  ///< the merged run's directory
  std::vector<std::string> shards;  ///< every shard's directory, any order
  bool no_png = false, json = false;
};

/// Reads every shard, checks that they are the parts of one sweep and writes the merged
/// outputs; reports what is wrong and returns the exit code.
int run_merge(const MergeOptions& o);

}  // namespace foveal::bench
