#pragma once
// The scripted mode's answers file of `foveal calibrate` and `foveal study run`: one
// answer per word, '#' starts a comment; each word kept with its line for messages.
// Here, not in the CLI, because the study's runner (foveal::study_render) reads it too.
#include <sstream>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/core/read_file.hpp"

namespace foveal::cli {

template <class T>
struct ScriptedWord {
  T value;
  int line;
};

/// `parse` turns one word into Result<T>; its error becomes "PATH:LINE: message".
template <class T, class Parse>
Result<std::vector<ScriptedWord<T>>> read_scripted_words(const std::string& path, Parse parse) {
  auto text = read_regular_file(path, kMaxJsonFileBytes, "answers file");
  if (!text) return text.error();
  std::istringstream in(*text);
  std::vector<ScriptedWord<T>> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string w;
    while (words >> w) {
      Result<T> v = parse(w);
      if (!v) return bad_input(path + ":" + std::to_string(n) + ": " + v.error().message);
      out.push_back({std::move(*v), n});
    }
  }
  return out;
}

}  // namespace foveal::cli
