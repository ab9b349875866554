#pragma once
// Reading JSON documents with limits: every JSON input (profiles, display models, view
// files, filter settings, glTF, control messages) goes through here, so a document nested
// deeper than kMaxJsonDepth or larger than its size limit is refused before any
// recursive code (nlohmann's copies and dumps, tinygltf's value parser) sees it.
#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "foveal/core/error.hpp"

namespace foveal {

/// Deepest nesting of arrays and objects accepted in any JSON input (docs/bad-input.md).
inline constexpr int kMaxJsonDepth = 64;
/// Largest configuration-style JSON file (profile, display model, view file, settings).
inline constexpr std::size_t kMaxJsonFileBytes = std::size_t{1} << 20;

struct JsonLimits {
  std::size_t max_bytes = kMaxJsonFileBytes;
  int max_depth = kMaxJsonDepth;
};

/// Checks the nesting depth of `text` by scanning its bytes (no recursion, no parse).
/// `where` starts the message: "FILE: JSON nested deeper than 64 levels (at byte N)".
Status check_json_depth(std::string_view text, const std::string& where, int max_depth = kMaxJsonDepth);

/// Parses `text` within `limits`; errors start with `where`.
Result<nlohmann::json> parse_json(std::string_view text, const std::string& where, JsonLimits limits = {});

/// As parse_json, for callers that only need "usable or not": a discarded value
/// (is_discarded()) for anything over the limits or not valid JSON.
nlohmann::json parse_json_or_discarded(std::string_view text, JsonLimits limits = {});

/// Reads and parses a regular file within `limits`. `what` names the kind of file in
/// messages ("profile", "display model").
Result<nlohmann::json> read_json_file(const std::string& path, const std::string& what, JsonLimits limits = {});

}  // namespace foveal
