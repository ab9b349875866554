// The described methods (foveal/image/method_description.hpp): one row each. A new one is
// a file beside this one that defines its MethodDescription, and a row here.
#include <cstring>

#include "foveal/image/method_description.hpp"

namespace foveal::render {

// Defined in this folder, one file per method.
const MethodDescription& inset_method();        // inset.cpp
const MethodDescription& inset_fixed_method();  // inset.cpp

const std::vector<const MethodDescription*>& described_methods() {
  static const std::vector<const MethodDescription*> list = {
      &inset_method(),        // inset: quad views' inner view on the gaze over a 1/σ outer view
      &inset_fixed_method(),  // inset-fixed: the same inner view held at the optical centre
  };
  return list;
}

Method described_method(std::size_t row) { return static_cast<Method>(kDescribedMethodBase + static_cast<int>(row)); }

const MethodDescription* describe(Method m) {
  const int row = static_cast<int>(m) - kDescribedMethodBase;
  if (row < 0 || static_cast<std::size_t>(row) >= described_methods().size()) return nullptr;
  return described_methods()[static_cast<std::size_t>(row)];
}

const std::vector<const MethodDescription*>& described_kernels() {
  static const std::vector<const MethodDescription*> kernels = [] {
    std::vector<const MethodDescription*> k;
    for (const MethodDescription* d : described_methods()) {
      bool seen = false;
      for (const MethodDescription* e : k) seen = seen || std::strcmp(e->kernel_name, d->kernel_name) == 0;
      if (!seen) k.push_back(d);
    }
    return k;
  }();
  return kernels;
}

int kernel_index(Method m) {
  const MethodDescription* d = describe(m);
  if (!d) return -1;
  const auto& k = described_kernels();
  for (std::size_t i = 0; i < k.size(); ++i)
    if (std::strcmp(k[i]->kernel_name, d->kernel_name) == 0) return static_cast<int>(i);
  return -1;
}

}  // namespace foveal::render
