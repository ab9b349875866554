// Writes the JOD validation's cases for the reference (docs/results/jod/run_reference.py):
// OUT/cases.json and each case's frames as PNG. usage: jod_cases_write RENDERS_DIR OUT_DIR
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "jod_cases.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: jod_cases_write RENDERS_DIR OUT_DIR\n");
    return 2;
  }
  const std::string renders = argv[1], out = argv[2];
  std::filesystem::create_directories(out);
  nlohmann::json cases = nlohmann::json::array();
  int i = 0;
  for (const auto& recipe : foveal::test::jod_case_recipes()) {
    auto c = recipe.make(renders);
    if (!c) {
      std::fprintf(stderr, "jod_cases_write: %s: %s\n", recipe.name.c_str(), c.error().message.c_str());
      return 2;
    }
    nlohmann::json j = {{"name", c->name}, {"fps", c->fps}, {"ref", nlohmann::json::array()}, {"test", nlohmann::json::array()}};
    for (std::size_t k = 0; k < c->ref.size(); ++k) {
      char name[64];
      for (const char* side : {"ref", "test"}) {
        std::snprintf(name, sizeof name, "%02d_%s_%02zu.png", i, side, k);
        const auto& img = std::string(side) == "ref" ? c->ref[k] : c->test[k];
        if (auto s = foveal::image::save_png(out + "/" + name, img); !s) {
          std::fprintf(stderr, "jod_cases_write: %s\n", s.error().message.c_str());
          return 1;
        }
        j[side].push_back(name);
      }
    }
    // null: not foveated; [x, y]: one fovea; [[x, y], ...]: one per frame.
    bool same = true;
    for (const auto& f : c->fovea)
      same = same && f.has_value() == c->fovea[0].has_value() && (!f || (f->x == c->fovea[0]->x && f->y == c->fovea[0]->y));
    if (same)
      j["fovea"] = c->fovea[0] ? nlohmann::json{c->fovea[0]->x, c->fovea[0]->y} : nlohmann::json(nullptr);
    else
      for (const auto& f : c->fovea) j["fovea"].push_back({f->x, f->y});
    cases.push_back(j);
    ++i;
  }
  std::ofstream(out + "/cases.json") << cases.dump(1) << "\n";
  std::printf("%d cases in %s\n", i, out.c_str());
  return 0;
}
