#include "calibrate/calibration_window.hpp"

#define GLFW_INCLUDE_NONE  // GL comes from foveal/render/gl.hpp (core profile)
#include <GLFW/glfw3.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <optional>
#include <tuple>
#include <utility>

#include "foveal/core/data_paths.hpp"
#include "foveal/render/compositor.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/render/window.hpp"
#include "calibrate/pixel_font.hpp"

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

/// Wraps words into lines of at most `width` characters.
std::string wrap(const std::string& text, std::size_t width) {
  std::string out, line;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!line.empty() && line.size() + 1 + word.size() > width) {
      out += line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    start = end + 1;
  }
  return out + line;
}

// The instruction in each eye's half, on a dark band near the bottom, so that a person
// wearing the headset reads it in whichever eye is shown.
void draw_instruction(GLuint fbo, int eye_w, const std::string& text) {
  const int scale = std::max(2, eye_w / 320);
  const std::string lines = wrap(text, static_cast<std::size_t>(std::max(10, (eye_w * 8 / 10) / (kGlyphAdvance * scale))));
  const int n_lines = 1 + static_cast<int>(std::count(lines.begin(), lines.end(), '\n'));
  const int height = (n_lines * kLineAdvance + 2) * scale, width = text_width(lines, scale) + 4 * scale;
  for (int x0 : {0, eye_w}) {
    const int left = x0 + (eye_w - width) / 2, bottom = 2 * kLineAdvance * scale;
    fill(fbo, left, bottom, width, height, 0.05f, 0.05f, 0.05f);
    for (const PixelRect& r : text_rects(lines, left + 2 * scale, bottom + height - scale, scale))
      fill(fbo, r.x, r.y, r.w, r.h, 0.95f, 0.95f, 0.6f);
  }
}

}  // namespace

std::string calibration_instruction(const CalibrationPrompt& p) {
  const bool miles = p.stage == CalibrationStage::dominant_eye;
  return std::string(calibration_stage_name(p.stage)) + ", trial " + std::to_string(p.trial + 1) + ": " + p.question +
         (miles ? " Keys: L left, R right" : " Keys: S same, D different") + "; Esc quits.";
}

Status run_calibration_window(Calibration& cal, const CalibrationWindowOptions& o, ValidationGaze* gaze,
                              CalibrationDisplay* display) {
  render::CompositorOptions co;  // the headset's own size, from the display model
  co.width = co.model.output_width();
  co.height = co.model.output_height();
  render::WindowOptions wo;
  wo.monitor = o.monitor;
  wo.width = co.width;  // windowed: the frames at their own size where the screen has room
  wo.height = co.height;
  wo.fit_to_monitor = true;
  wo.title = "foveal calibrate: L/R which eye keeps the target framed; S same, D different; Esc quits";
  auto window = render::Window::open(wo);
  if (!window) return window.error();
  auto scene = render::load_scene(o.scene.empty() ? data_path("data/scenes/Dungeon/dungeon_simplified.gltf") : o.scene);
  if (!scene) return scene.error();
  auto comp = render::Compositor::create(co);
  if (!comp) return comp.error();
  CalibrationDisplay shown;
  shown.frame_width = co.width;
  shown.frame_height = co.height;
  std::tie(shown.shown_width, shown.shown_height) = window->framebuffer_size();
  shown.monitor = o.monitor;
  if (display) *display = shown;
  if (shown.scale() < 0.99)
    std::fprintf(stderr,
                 "foveal calibrate: warning: the %dx%d frames are shown at %dx%d (%.2fx): shrunk, they hide the "
                 "foveation being judged and sigma comes out too high. Calibrate on the headset: --monitor NAME\n",
                 shown.frame_width, shown.frame_height, shown.shown_width, shown.shown_height, shown.scale());

  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::array<bool, 15> pad{};
  int fixation_trial = -1;  // the validation trial whose fixation window is open
  // Every prompt is told on stderr as it comes, also those answered by keys queued up
  // while a slow frame rendered.
  std::string told;
  const auto tell = [&] {
    if (cal.done()) return;
    if (std::string now = calibration_instruction(cal.prompt()); now != told) {
      std::fprintf(stderr, "foveal calibrate: %s\n", now.c_str());
      told = std::move(now);
    }
  };
  while (!cal.done()) {
    if (window->should_close()) return bad_input("calibration quit: the window was closed; nothing was saved");
    tell();
    const CalibrationPrompt& p = cal.prompt();
    const std::string instruction = told;
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
    draw_instruction(comp->output_framebuffer(), comp->eye_width(),
                     shown.scale() < 0.99 ? instruction + " (Shown shrunk: use --monitor on the headset.)" : instruction);
    window->present(comp->output_framebuffer(), comp->width(), comp->height());
    // Every answer given since the last frame, in order; one that does not fit the
    // prompt (left/right to a comparison) is ignored.
    for (int key : window->take_keys()) {
      if (key == GLFW_KEY_ESCAPE) return bad_input("calibration quit (Esc); nothing was saved");
      if (auto a = key_answer(key); a && !cal.done()) (void)cal.answer(*a);
      tell();
    }
    if (auto a = gamepad_answer(pad); a && !cal.done()) (void)cal.answer(*a);
  }
  if (gaze && fixation_trial >= 0) gaze->fixations.back().second = monotonic_now_ns();
  return {};
}

}  // namespace foveal::cmd
