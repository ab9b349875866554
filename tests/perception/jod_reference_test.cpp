// The native FovVideoVDP against the reference's figures on the validation cases
// (tests/perception/data/jod_reference.csv; docs/metrics.md, "JOD"): median |ΔJOD| ≤ 0.1,
// max ≤ 0.3 (the target) and ≤ 0.002 (what it reaches); a perturbed model fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "foveal/perception/jod.hpp"
#include "jod_cases.hpp"
#include "test_support.hpp"

namespace foveal::test {
namespace {

std::map<std::string, double> reference_figures(const std::string& file) {
  std::ifstream in(source_path("tests/perception/data/" + file));
  std::map<std::string, double> out;
  std::string line;
  std::getline(in, line);  // name,frames,jod
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string name, frames, jod;
    std::getline(ss, name, ',');
    std::getline(ss, frames, ',');
    std::getline(ss, jod, ',');
    out[name] = std::stod(jod);
  }
  return out;
}

double native_jod(const JodCase& c, const perception::Parameters& p) {
  auto model = DisplayModel::load(source_path("tests/perception/data/vive_window_384x224.json"));
  EXPECT_TRUE(model) << model.error().message;
  const int w = c.ref[0].width, h = c.ref[0].height;
  perception::JodMetric m(perception::eye_geometry(*model, Eye::left, w, h), perception::Photometry{}, p);
  const auto fix = [&](std::size_t k) -> std::optional<perception::Fixation> {
    if (!c.fovea[k]) return std::nullopt;
    return perception::Fixation{c.fovea[k]->x * w, c.fovea[k]->y * h};
  };
  if (c.fps == 0) {
    auto s = m.still(c.ref[0], c.test[0], fix(0));
    EXPECT_TRUE(s) << s.error().message;
    return s ? s->jod : NAN;
  }
  auto v = m.video(c.fps);
  EXPECT_TRUE(v);
  for (std::size_t k = 0; k < c.ref.size(); ++k) EXPECT_TRUE(v->push(c.ref[k], c.test[k], fix(k)));
  auto s = v->score();
  EXPECT_TRUE(s);
  return s ? s->jod : NAN;
}

struct Agreement {
  double median = 0, max = 0;
  int n = 0;
};

// |ΔJOD| over the cases `pick` selects, printed per case.
template <class Pick>
Agreement agreement(const perception::Parameters& p, Pick pick, bool print, const std::string& file = "jod_reference.csv") {
  const auto ref = reference_figures(file);
  std::vector<double> d;
  for (const auto& recipe : jod_case_recipes()) {
    if (!pick(recipe.name)) continue;
    auto it = ref.find(recipe.name);
    EXPECT_NE(it, ref.end()) << recipe.name << ": no reference figure";
    if (it == ref.end()) continue;
    auto c = recipe.make(source_path("tests/perception/data/renders"));
    EXPECT_TRUE(c) << recipe.name << ": " << c.error().message;
    if (!c) continue;
    const double jod = native_jod(*c, p);
    d.push_back(std::abs(jod - it->second));
    if (print) std::printf("%-32s reference %8.4f  native %8.4f  |d| %.4f\n", recipe.name.c_str(), it->second, jod, d.back());
  }
  Agreement a;
  a.n = static_cast<int>(d.size());
  if (d.empty()) return a;
  std::sort(d.begin(), d.end());
  a.median = d.size() % 2 ? d[d.size() / 2] : 0.5 * (d[d.size() / 2 - 1] + d[d.size() / 2]);
  a.max = d.back();
  return a;
}

TEST(JodReference, NativeAgreesWithTheReferenceOnEveryCase) {
  const Agreement a = agreement(perception::Parameters{}, [](const std::string&) { return true; }, true);
  std::printf("%d cases: median |dJOD| %.5f, max %.5f\n", a.n, a.median, a.max);
  EXPECT_GE(a.n, 40);
  EXPECT_LE(a.median, 0.1);  // issue 28's target
  EXPECT_LE(a.max, 0.3);
  // What the native metric reaches (median 2e-5, max 8e-5 when written), with a margin for
  // other compilers' float rounding.
  EXPECT_LE(a.max, 0.002);
}

// Release 1.0's calibration (the paper's) against the reference run with it; the reference
// ships no CSF table for its k_cm, so it read one made from foveal's formula
// (docs/results/jod/make_csf_table.py): this checks everything but the CSF, which
// Csf.MatchesTheReferenceTableAtGridPoints checks at release 1.2's k_cm.
TEST(JodReference, Release10AgreesWithTheReference) {
  const Agreement a = agreement(perception::Parameters::release_1_0(), [](const std::string&) { return true; }, false,
                                "jod_reference_release_1_0.csv");
  std::printf("release 1.0, %d cases: median |dJOD| %.5f, max %.5f\n", a.n, a.median, a.max);
  EXPECT_GE(a.n, 40);
  EXPECT_LE(a.median, 0.1);
  EXPECT_LE(a.max, 0.002);
}

// The check can fail: 2 dB more sensitivity or a masking exponent of 2.2 instead of 2.4.
TEST(JodReference, APerturbedModelFailsTheCheck) {
  const auto stills = [](const std::string& name) { return name.rfind("v_", 0) != 0; };
  perception::Parameters louder;
  louder.sensitivity_correction_db += 2.0;
  const Agreement a = agreement(louder, stills, false);
  std::printf("sensitivity +2 dB: median %.4f, max %.4f\n", a.median, a.max);
  EXPECT_TRUE(a.median > 0.1 || a.max > 0.3);
  perception::Parameters mask;
  mask.mask_p = 2.2;
  const Agreement b = agreement(mask, stills, false);
  std::printf("mask_p 2.2: median %.4f, max %.4f\n", b.median, b.max);
  EXPECT_TRUE(b.median > 0.1 || b.max > 0.3);
}

}  // namespace
}  // namespace foveal::test
