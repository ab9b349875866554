#pragma once
// Writing JSON text. Every JSON writer in foveal (summaries, --json output, control
// messages, profiles) goes through json_text: strings can carry file names, and Linux
// file names are bytes, not necessarily UTF-8. nlohmann's plain dump() throws
// type_error 316 on such bytes; here each invalid byte becomes U+FFFD instead.
#include <string>

#include <nlohmann/json.hpp>

namespace foveal {

/// `j` as JSON text, never throwing on invalid UTF-8. indent < 0: one line;
/// otherwise pretty-printed with that many spaces per level (as dump(indent)).
inline std::string json_text(const nlohmann::json& j, int indent = -1) {
  return j.dump(indent, ' ', /*ensure_ascii=*/false, nlohmann::json::error_handler_t::replace);
}

}  // namespace foveal
