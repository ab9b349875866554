#pragma once
// The JOD validation's cases (docs/metrics.md, "JOD"): made deterministically from the GL
// renders in tests/perception/data/renders, the same pixels for the native metric (the test)
// and for the reference (jod_cases_write writes them out for run_reference.py).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/image/image.hpp"
#include "foveal/perception/jod_files.hpp"

namespace foveal::test {

struct JodCase {
  std::string name;
  double fps = 0;  ///< 0: a still
  /// One per frame (a still: one); none: not foveated.
  std::vector<std::optional<perception::NormFovea>> fovea;
  std::vector<image::Image> ref, test;
};

/// The recipes, in order; each builds its case from the renders folder.
struct JodCaseRecipe {
  std::string name;
  std::function<Result<JodCase>(const std::string& renders_dir)> make;
};
std::vector<JodCaseRecipe> jod_case_recipes();

}  // namespace foveal::test
