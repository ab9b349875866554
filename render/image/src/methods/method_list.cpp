// The foveation methods (foveal/image/method_description.hpp): one row each, in the order
// of the Method values. A new one is a file beside this one that defines its
// MethodDescription, and a row at the end here (the order names bench files and goldens).
#include <cstring>

#include "foveal/image/method_description.hpp"

namespace foveal::render {

// Defined in this folder, one file per method or per family sharing a kernel.
const MethodDescription& full_method();         // rmfr.cpp
const MethodDescription& rmfr_method();         // rmfr.cpp
const MethodDescription& kfr_method();          // kfr.cpp
const MethodDescription& hyperbolic_method();   // layers.cpp
const MethodDescription& linear_method();       // layers.cpp
const MethodDescription& uniform_method();      // rmfr.cpp
const MethodDescription& fixed_method();        // rmfr.cpp
const MethodDescription& inset_method();        // inset.cpp
const MethodDescription& inset_fixed_method();  // inset.cpp

const std::vector<const MethodDescription*>& described_methods() {
  static const std::vector<const MethodDescription*> list = {
      &full_method(),         // full: every pixel shaded, the reference
      &rmfr_method(),         // rmfr: the rectilinear map (Ye et al. 2019)
      &kfr_method(),          // kfr: kernel log-polar (Meng et al. 2018)
      &hyperbolic_method(),   // hyperbolic: three nested layers (Guenter et al. 2012)
      &linear_method(),       // linear: rate falling linearly 10°-20° (Weier et al. 2016)
      &uniform_method(),      // uniform: an even W/σ × H/σ grid, no eye tracking
      &fixed_method(),        // fixed: RMFR with the fovea at the optical centre
      &inset_method(),        // inset: quad views' inner view on the gaze over a 1/σ outer view
      &inset_fixed_method(),  // inset-fixed: the same inner view held at the optical centre
  };
  return list;
}

Method described_method(std::size_t row) { return static_cast<Method>(row); }

const MethodDescription* describe(Method m) {
  const int row = static_cast<int>(m);
  if (row < 0 || static_cast<std::size_t>(row) >= described_methods().size()) return nullptr;
  return described_methods()[static_cast<std::size_t>(row)];
}

const std::vector<const MethodKernel*>& method_kernels() {
  static const std::vector<const MethodKernel*> kernels = [] {
    std::vector<const MethodKernel*> k;
    for (const MethodDescription* d : described_methods()) {
      bool seen = false;
      for (const MethodKernel* e : k) seen = seen || std::strcmp(e->name, d->kernel->name) == 0;
      if (!seen) k.push_back(d->kernel);
    }
    return k;
  }();
  return kernels;
}

int kernel_index(Method m) {
  const MethodDescription* d = describe(m);
  if (!d) return -1;
  const auto& k = method_kernels();
  for (std::size_t i = 0; i < k.size(); ++i)
    if (std::strcmp(k[i]->name, d->kernel->name) == 0) return static_cast<int>(i);
  return -1;
}

}  // namespace foveal::render
