#include "calibration_window.hpp"

#define GLFW_INCLUDE_NONE  // GL comes from foveal/render/gl.hpp (core profile)
#include <GLFW/glfw3.h>

#include <array>
#include <chrono>
#include <optional>

#include "foveal/core/data_paths.hpp"
#include "foveal/render/compositor.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/render/window.hpp"

namespace foveal::cmd {

namespace {

// Keys and gamepad buttons to answers: L/← left, R/→ right, S/Enter/A same, D/B different,
// LB left, RB right.
std::optional<Answer> key_answer(int key) {
  switch (key) {
    case GLFW_KEY_L: case GLFW_KEY_LEFT: return Answer::left;
    case GLFW_KEY_R: case GLFW_KEY_RIGHT: return Answer::right;
    case GLFW_KEY_S: case GLFW_KEY_ENTER: return Answer::same;
    case GLFW_KEY_D: return Answer::different;
    default: return std::nullopt;
  }
}

std::optional<Answer> gamepad_answer(std::array<bool, 15>& was_down) {
  GLFWgamepadstate st;
  if (!glfwJoystickIsGamepad(GLFW_JOYSTICK_1) || !glfwGetGamepadState(GLFW_JOYSTICK_1, &st)) return std::nullopt;
  const std::pair<int, Answer> map[] = {{GLFW_GAMEPAD_BUTTON_A, Answer::same}, {GLFW_GAMEPAD_BUTTON_B, Answer::different},
                                        {GLFW_GAMEPAD_BUTTON_LEFT_BUMPER, Answer::left},
                                        {GLFW_GAMEPAD_BUTTON_RIGHT_BUMPER, Answer::right}};
  std::optional<Answer> out;
  for (auto [button, answer] : map) {
    const bool down = st.buttons[button] == GLFW_PRESS;
    if (down && !was_down[static_cast<std::size_t>(button)]) out = answer;
    was_down[static_cast<std::size_t>(button)] = down;
  }
  return out;
}

void fill(GLuint fbo, int x, int y, int w, int h, float r, float g, float b) {
  glEnable(GL_SCISSOR_TEST);
  glScissor(x, y, w, h);
  const float c[4] = {r, g, b, 1.0f};
  glClearNamedFramebufferfv(fbo, GL_COLOR, 0, c);
  glDisable(GL_SCISSOR_TEST);
}

// The Miles test's stimulus: black everywhere, a frame with a target in the shown eye.
void draw_miles(GLuint fbo, int eye_w, int h, Eye shown) {
  fill(fbo, 0, 0, 2 * eye_w, h, 0, 0, 0);
  const int x0 = shown == Eye::left ? 0 : eye_w, cx = x0 + eye_w / 2, cy = h / 2;
  const int half = eye_w / 6, t = std::max(2, eye_w / 150);
  fill(fbo, cx - half, cy - half, 2 * half, t, 0.9f, 0.9f, 0.9f);
  fill(fbo, cx - half, cy + half - t, 2 * half, t, 0.9f, 0.9f, 0.9f);
  fill(fbo, cx - half, cy - half, t, 2 * half, 0.9f, 0.9f, 0.9f);
  fill(fbo, cx + half - t, cy - half, t, 2 * half, 0.9f, 0.9f, 0.9f);
  const int dot = std::max(4, eye_w / 60);
  fill(fbo, cx - dot / 2, cy - dot / 2, dot, dot, 0.95f, 0.2f, 0.1f);
}

}  // namespace

Status run_calibration_window(Calibration& cal, const CalibrationWindowOptions& o, ValidationGaze* gaze) {
  render::WindowOptions wo;
  wo.monitor = o.monitor;
  wo.title = "foveal calibrate: L/R which eye keeps the target framed; S same, D different; Esc quits";
  auto window = render::Window::open(wo);
  if (!window) return window.error();
  auto scene = render::load_scene(o.scene.empty() ? data_path("data/scenes/Dungeon/dungeon_simplified.gltf") : o.scene);
  if (!scene) return scene.error();
  render::CompositorOptions co;  // the headset's own size, from the display model
  co.width = co.model.output_width();
  co.height = co.model.output_height();
  auto comp = render::Compositor::create(co);
  if (!comp) return comp.error();

  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::array<bool, 15> pad{};
  int fixation_trial = -1;  // the validation trial whose fixation window is open
  while (!cal.done()) {
    if (window->should_close()) return bad_input("calibration quit: the window was closed; nothing was saved");
    const CalibrationPrompt& p = cal.prompt();
    if (o.gaze && gaze) {
      // Everything the tracker has delivered; kept only while a fixation target shows.
      for (ReadResult r = o.gaze->next(std::chrono::milliseconds(0)); r.status == ReadStatus::sample;
           r = o.gaze->next(std::chrono::milliseconds(0)))
        if (fixation_trial >= 0) gaze->samples.push_back(r.sample);
      const bool validating = p.stage == CalibrationStage::validation;
      if (fixation_trial >= 0 && (!validating || p.trial != fixation_trial)) {
        gaze->fixations.back().second = monotonic_now_ns();  // answered: the window closes
        fixation_trial = -1;
      }
      if (validating && fixation_trial < 0) {
        const TimeNs now = monotonic_now_ns();
        gaze->fixations.push_back({now + ValidationGaze::kSettleNs, now + ValidationGaze::kSettleNs});
        fixation_trial = p.trial;
      }
    }
    if (p.stage == CalibrationStage::dominant_eye) {
      draw_miles(comp->output_framebuffer(), comp->eye_width(), comp->height(), p.shown_eye);
    } else {
      // Alternate the full-resolution reference and the test pair; the user judges the change.
      const double t = std::chrono::duration<double>(Clock::now() - start).count();
      const bool test_phase = static_cast<long>(t / o.flip_s) % 2 == 1;
      render::FrameParams f = render::efr_frame(render::Method::rmfr, Eye::right, 1, 1, 0.3, 0.3);
      f.eyes[0].sigma = test_phase ? p.sigma_left : 1.0;
      f.eyes[1].sigma = test_phase ? p.sigma_right : 1.0;
      if (auto r = comp->render(*scene, f); !r) return r.error();
      // Validation trials carry a fixation target straight ahead in each eye: the gaze
      // recorded meanwhile gives the accuracy and precision (calibrate --gaze-log).
      if (p.stage == CalibrationStage::validation) {
        const int dot = std::max(4, comp->eye_width() / 120);
        for (int x0 : {0, comp->eye_width()})
          fill(comp->output_framebuffer(), x0 + comp->eye_width() / 2 - dot / 2, comp->height() / 2 - dot / 2, dot, dot,
               0.95f, 0.2f, 0.1f);
      }
    }
    window->present(comp->output_framebuffer(), comp->width(), comp->height());
    // Every answer given since the last frame, in order; one that does not fit the
    // prompt (left/right to a comparison) is ignored.
    for (int key : window->take_keys()) {
      if (key == GLFW_KEY_ESCAPE) return bad_input("calibration quit (Esc); nothing was saved");
      if (auto a = key_answer(key); a && !cal.done()) (void)cal.answer(*a);
    }
    if (auto a = gamepad_answer(pad); a && !cal.done()) (void)cal.answer(*a);
  }
  if (gaze && fixation_trial >= 0) gaze->fixations.back().second = monotonic_now_ns();
  return {};
}

}  // namespace foveal::cmd
