#pragma once
// A bench sweep split over processes (docs/bench.md, "On a cluster"). Every point of the
// sweep's grid (scene × method × level, f-grid point, angle, ...) gets the next index in
// the order a single run visits it; `--shard K/N` runs the points whose index is K-1
// modulo N (round robin, so that cheap and dear points spread evenly) and tags every row
// it writes with its point. `foveal bench merge` sorts the shards' rows back into the
// single run's order. Nothing here knows what the grid is: a new axis or experiment
// only calls take() at each of its points and adds its rows there. An experiment whose
// loop visits its points again and again (frame by frame, say) takes them all first,
// keeping the index take(&point) gives, and adds rows naming that point. Every table and
// list, in a run as in a merge, is in point order (a point's rows in the order added).
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/error.hpp"

namespace foveal::bench {

/// The most parts a sweep is split into (`--shard K/N`, shard.json's "shard").
inline constexpr int kMaxShards = 1000000;

/// `--shard K/N`: the K-th of N disjoint parts; 1/1 is the whole sweep.
struct Shard {
  int k = 1, n = 1;
  std::string text() const { return std::to_string(k) + "/" + std::to_string(n); }
};
Result<Shard> parse_shard(const std::string& text);

/// The rows of a sweep, collected point by point: CSV tables (one per output file) and
/// JSON lists (items of bench.json), each row tagged with the point that made it.
class SweepRows {
 public:
  explicit SweepRows(Shard shard = {}) : shard_(shard) {}

  /// Starts the next point of the grid; true when this shard runs it (and then adds the
  /// point's rows before the next take()).
  bool take();
  bool take(std::size_t* point);  ///< also: the point's index
  /// Declares a table: written (header only) even when this shard adds no row to it.
  void table(const std::string& file, const std::string& header);
  /// A CSV line (no newline) or a list item of the point take() started.
  void add_line(const std::string& file, std::string line);
  void add_item(const std::string& list, nlohmann::json item);
  /// The same for a point taken earlier (its index from take(&point)).
  void add_line(const std::string& file, std::string line, std::size_t point);
  void add_item(const std::string& list, nlohmann::json item, std::size_t point);

  const Shard& shard() const { return shard_; }
  /// Points seen so far: the grid's size once the sweep has run.
  std::size_t points() const { return next_; }
  std::vector<std::string> tables() const;
  /// A table as CSV text: the header, then the lines in point order.
  std::string csv(const std::string& file) const;
  /// A list's items in point order (an empty array for a list nobody added to).
  nlohmann::json list(const std::string& name) const;
  std::size_t lines(const std::string& file) const;

  /// The shard file's form (shard.json, "rows") and back; `where` names the file.
  nlohmann::json to_json() const;
  static Result<SweepRows> from_json(const nlohmann::json& j, const std::string& where);
  /// Joins the N shards of one sweep (any order) into the rows of the single run.
  /// `names` (one per part) name them in messages.
  static Result<SweepRows> merge(const std::vector<SweepRows>& parts, const std::vector<std::string>& names);

 private:
  template <class T>
  struct Tagged {
    std::size_t point;
    T value;
  };
  struct Table {
    std::string header;
    std::vector<Tagged<std::string>> lines;
  };
  std::size_t current() const;
  bool mine(std::size_t point) const;
  void sort();

  Shard shard_;
  std::size_t next_ = 0;
  bool running_ = false;  ///< the point take() last started is this shard's
  std::map<std::string, Table> tables_;
  std::map<std::string, std::vector<Tagged<nlohmann::json>>> lists_;
};

}  // namespace foveal::bench
