// What a frame is asked for: the EFR helper (efr_frame: each eye its own level), where
// temporal accumulation applies, and the pipelines by name (parse_pipeline and the lists
// the CLI and bench show), and where blended surfaces are shaded (BlendAt) by name.
#include <string>
#include <vector>

#include "foveal/image/method_description.hpp"
#include "foveal/render/compositor.hpp"

namespace foveal::render {

bool temporal_applies(Method m, Pipeline p) {
  const MethodDescription* d = describe(m);
  return p == Pipeline::visibility && m != Method::full && d && d->kernel && d->kernel->rmfr_passes;
}

FrameParams efr_frame(Method method, Eye dominant, double sigma_d, double sigma_nd, double fx, double fy) {
  FrameParams p;
  p.method = method;
  for (Eye e : kEyes) {
    EyeFoveation& f = p.eyes[static_cast<std::size_t>(e)];
    f.sigma = e == dominant ? sigma_d : sigma_nd;
    f.fx = fx;
    f.fy = fy;
  }
  return p;
}

const std::vector<Pipeline>& all_pipelines() {
  static const std::vector<Pipeline> p = {Pipeline::gbuffer, Pipeline::visibility};
  return p;
}

const char* pipeline_name(Pipeline p) { return p == Pipeline::visibility ? "visibility" : "gbuffer"; }

const std::vector<std::string>& pipeline_names() {
  static const std::vector<std::string> n = {"gbuffer", "visibility"};
  return n;
}

Result<Pipeline> parse_pipeline(const std::string& s) {
  for (Pipeline p : all_pipelines())
    if (s == pipeline_name(p)) return p;
  return bad_input("unknown pipeline '" + s + "' (gbuffer, visibility)");
}

const char* blend_at_name(BlendAt b) { return b == BlendAt::samples ? "samples" : "output"; }

const std::vector<std::string>& blend_at_names() {
  static const std::vector<std::string> n = {"output", "samples"};
  return n;
}

Result<BlendAt> parse_blend_at(const std::string& s) {
  for (BlendAt b : {BlendAt::output, BlendAt::samples})
    if (s == blend_at_name(b)) return b;
  return bad_input("unknown blend place '" + s + "' (output, samples)");
}

Status check_blend_at(BlendAt at, Pipeline pipeline) {
  if (at == BlendAt::samples && pipeline != Pipeline::visibility)
    return bad_input("--blend-at samples needs --pipeline visibility (the G-buffer pipeline blends at output)");
  return {};
}

}  // namespace foveal::render
