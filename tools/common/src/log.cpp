#include "foveal/tools/log.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>

namespace foveal::log {

namespace {
std::atomic<int> g_level{static_cast<int>(Level::info)};
const char* g_program = "foveal";
const char* const kNames[] = {"error", "warn", "info", "debug"};
}  // namespace

void init(const char* program, int verbosity) {
  g_program = program;
  int l = static_cast<int>(Level::info);
  if (const char* env = std::getenv("FOVEAL_LOG"))
    for (int i = 0; i < 4; ++i)
      if (std::strcmp(env, kNames[i]) == 0) l = i;
  g_level = std::clamp(l + verbosity, 0, 3);
}

Level level() { return static_cast<Level>(g_level.load()); }
bool enabled(Level l) { return static_cast<int>(l) <= g_level.load(); }

void write(Level l, const std::string& msg) {
  if (!enabled(l)) return;
  std::fprintf(stderr, "%s: %s: %s\n", g_program, kNames[static_cast<int>(l)], msg.c_str());
}

}  // namespace foveal::log
