#pragma once
// Pass timing: GL_TIMESTAMP queries at the compositor's pass boundaries, charged to
// the pass each interval ends (PassTimes in compositor.hpp). Medians: pass_timing.cpp.
#include <cstddef>
#include <vector>

#include "foveal/render/compositor.hpp"
#include "foveal/render/gl.hpp"
#include "foveal/render/gl_objects.hpp"

namespace foveal::render::detail {

// Which pass a GPU timestamp interval belongs to.
enum class Pass { shadow, gbuffer, mapping, lighting, inverse, blend };

// GL_TIMESTAMP queries at pass boundaries, read back once the frame is finished.
class PassTimer {
 public:
  void begin_frame() { count_ = 0; }
  void mark(Pass finished) {
    if (count_ >= queries_.size()) {
      queries_.push_back(gl::make_query(GL_TIMESTAMP));
      passes_.push_back(finished);
    }
    passes_[count_] = finished;
    glQueryCounter(queries_[count_++].id(), GL_TIMESTAMP);
  }
  // Call after glFinish. Interval i (mark i-1 -> mark i) is charged to passes_[i].
  void collect(PassTimes& t) const {
    std::vector<GLuint64> stamp(count_);
    for (std::size_t i = 0; i < count_; ++i) glGetQueryObjectui64v(queries_[i].id(), GL_QUERY_RESULT, &stamp[i]);
    for (std::size_t i = 1; i < count_; ++i) {
      const double ms = static_cast<double>(stamp[i] - stamp[i - 1]) / 1e6;
      switch (passes_[i]) {
        case Pass::shadow: t.shadow += ms; break;
        case Pass::gbuffer: t.gbuffer += ms; break;
        case Pass::mapping: t.mapping += ms; break;
        case Pass::lighting: t.lighting += ms; break;
        case Pass::inverse: t.inverse += ms; break;
        case Pass::blend: t.blend += ms; break;
      }
    }
    if (count_ > 1) t.gpu_total = static_cast<double>(stamp[count_ - 1] - stamp[0]) / 1e6;
  }

 private:
  std::vector<gl::Query> queries_;
  std::vector<Pass> passes_;
  std::size_t count_ = 0;
};

}  // namespace foveal::render::detail
