#include "foveal/core/json_file.hpp"

#include "foveal/core/read_file.hpp"

namespace foveal {

namespace {

// The byte offset where nesting first exceeds `max_depth`, or npos. Brackets inside
// strings do not count; for valid JSON this is exactly the parser's depth.
std::size_t too_deep_at(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::string_view::npos;
}

}  // namespace

Status check_json_depth(std::string_view text, const std::string& where, int max_depth) {
  const std::size_t at = too_deep_at(text, max_depth);
  if (at == std::string_view::npos) return {};
  return bad_input(where + ": JSON nested deeper than " + std::to_string(max_depth) + " levels (at byte " +
                   std::to_string(at) + ")");
}

Result<nlohmann::json> parse_json(std::string_view text, const std::string& where, JsonLimits limits) {
  if (text.size() > limits.max_bytes)
    return bad_input(where + ": JSON of " + std::to_string(text.size()) + " bytes, more than the " +
                     describe_bytes(limits.max_bytes) + " accepted");
  if (Status s = check_json_depth(text, where, limits.max_depth); !s) return s.error();
  nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return bad_input(where + ": not valid JSON");
  return j;
}

nlohmann::json parse_json_or_discarded(std::string_view text, JsonLimits limits) {
  auto j = parse_json(text, "", limits);
  if (!j) return nlohmann::json(nlohmann::json::value_t::discarded);
  return std::move(*j);
}

Result<nlohmann::json> read_json_file(const std::string& path, const std::string& what, JsonLimits limits) {
  auto text = read_regular_file(path, limits.max_bytes, what);
  if (!text) return text.error();
  return parse_json(*text, path, limits);
}

}  // namespace foveal
