#include "inset_quality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "foveal/core/display_model.hpp"
#include "foveal/runtime/inset_levels.hpp"
#include "foveal/runtime/profile.hpp"

namespace foveal::openxr {

struct InsetQuality::Impl {
  InsetLevelTable table;
  EyeFrustum eye;
  double target = 10;
};

InsetQuality InsetQuality::from_environment() {
  const char* q = std::getenv("FOVEAL_OPENXR_QUALITY");
  const char* d = std::getenv("FOVEAL_OPENXR_DISPLAY");
  return from(q ? q : "", d && *d ? d : "htc_vive_pro_eye");
}

InsetQuality InsetQuality::from(const std::string& quality, const std::string& display) {
  InsetQuality out;
  auto fail = [&](const std::string& why) {
    out.problem_ = "FOVEAL_OPENXR_QUALITY: " + why + ": using FOVEAL_OPENXR_INSET and foveald's levels";
    return out;
  };
  auto target = parse_quality(quality, "FOVEAL_OPENXR_QUALITY");
  if (!target) return fail(target.error().message);
  if (!*target) return out;
  const std::string model_path = display_model_path(display);
  auto model = DisplayModel::load(model_path);
  if (!model) return fail(model.error().message);
  const std::string path = inset_levels_path(model_path);
  auto table = InsetLevelTable::load(path);
  if (!table) return fail(table.error().message);
  if (table->display != model->name)
    return fail(path + " is the inset table of display '" + table->display + "', not of '" + model->name + "'");
  auto impl = std::make_shared<Impl>();
  impl->table = std::move(*table);
  impl->eye = model->eye(Eye::left);
  impl->target = **target;
  out.impl_ = std::move(impl);
  return out;
}

bool InsetQuality::apply(const float sigma[2], InsetSettings& s, float density[2]) const {
  if (!impl_) return false;
  const int dominant = sigma[0] < sigma[1] ? 0 : 1;  // a tie: the right eye, as foveald's default profile
  const double ratio = std::clamp(static_cast<double>(sigma[1 - dominant]) / sigma[dominant], 1.0, 16.0);
  auto l = choose_inset_levels(impl_->table, impl_->target, std::isfinite(ratio) ? ratio : 1.0, impl_->eye);
  if (!l) return false;
  s.foveated_share_x = static_cast<float>(l->share_x);
  s.foveated_share_y = static_cast<float>(l->share_y);
  density[dominant] = static_cast<float>(1 / l->sigma_d);
  density[1 - dominant] = static_cast<float>(1 / l->sigma_nd);
  return true;
}

}  // namespace foveal::openxr
