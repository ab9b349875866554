#include "foveal/runtime/cli.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "foveal/core/json_text.hpp"

namespace foveal::cli {

int report(const Error& e, const char* program) {
  std::fprintf(stderr, "%s: error: %s\n", program, e.message.c_str());
  return e.kind == ErrorKind::internal ? kExitFailure : kExitBadInput;
}

void warn(const std::string& message, const char* program) {
  std::fprintf(stderr, "%s: warning: %s\n", program, message.c_str());
}

void print_json(const nlohmann::json& j) { std::cout << json_text(j, 2) << std::endl; }

Progress::Progress(std::string label, std::uint64_t total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled && ::isatty(STDERR_FILENO)) {}

Progress::~Progress() { finish(); }

void Progress::update(std::uint64_t done) {
  if (!enabled_ || total_ == 0) return;
  const int permille = static_cast<int>(1000 * std::min(done, total_) / total_);
  if (permille == last_permille_) return;
  last_permille_ = permille;
  constexpr int kWidth = 30;
  const int filled = permille * kWidth / 1000;
  std::fprintf(stderr, "\r%s [%.*s%*s] %5.1f%%", label_.c_str(), filled, "##############################",
               kWidth - filled, "", permille / 10.0);
  std::fflush(stderr);
}

void Progress::finish() {
  if (!enabled_ || finished_) return;
  finished_ = true;
  update(total_);
  std::fprintf(stderr, "\n");
}

}  // namespace foveal::cli
