#include "foveal/study/study_window.hpp"

#define GLFW_INCLUDE_NONE  // GL comes from foveal/render/gl.hpp (core profile)
#include <GLFW/glfw3.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <optional>

namespace foveal {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// 1-5 on the number row or keypad; the arrows for 2AFC's first/second.
std::optional<int> key_response(int key, StudyDesign d) {
  if (key >= GLFW_KEY_1 && key <= GLFW_KEY_5) return key - GLFW_KEY_1 + 1;
  if (key >= GLFW_KEY_KP_1 && key <= GLFW_KEY_KP_5) return key - GLFW_KEY_KP_1 + 1;
  if (d == StudyDesign::two_afc && key == GLFW_KEY_LEFT) return 1;
  if (d == StudyDesign::two_afc && key == GLFW_KEY_RIGHT) return 2;
  return std::nullopt;
}

struct Gamepad {
  std::array<bool, GLFW_GAMEPAD_BUTTON_LAST + 1> was_down{};
  /// Buttons newly pressed since the last call.
  std::vector<int> pressed() {
    std::vector<int> out;
    GLFWgamepadstate st;
    if (!glfwJoystickIsGamepad(GLFW_JOYSTICK_1) || !glfwGetGamepadState(GLFW_JOYSTICK_1, &st)) return out;
    for (int b = 0; b <= GLFW_GAMEPAD_BUTTON_LAST; ++b) {
      const bool down = st.buttons[b] == GLFW_PRESS;
      if (down && !was_down[static_cast<std::size_t>(b)]) out.push_back(b);
      was_down[static_cast<std::size_t>(b)] = down;
    }
    return out;
  }
};

// 2AFC: LB first, RB second. Random test: B 1, X 2, Y 3, RB 4, A 5 (no difference).
std::optional<int> button_response(int button, StudyDesign d) {
  if (d == StudyDesign::two_afc) {
    if (button == GLFW_GAMEPAD_BUTTON_LEFT_BUMPER) return 1;
    if (button == GLFW_GAMEPAD_BUTTON_RIGHT_BUMPER) return 2;
    return std::nullopt;
  }
  switch (button) {
    case GLFW_GAMEPAD_BUTTON_B: return 1;
    case GLFW_GAMEPAD_BUTTON_X: return 2;
    case GLFW_GAMEPAD_BUTTON_Y: return 3;
    case GLFW_GAMEPAD_BUTTON_RIGHT_BUMPER: return 4;
    case GLFW_GAMEPAD_BUTTON_A: return 5;
    default: return std::nullopt;
  }
}

enum class Phase { first, blank, second, respond, pause };

}  // namespace

Status run_study_window(StudySession& session, StudyFrames& frames, render::Window& window) {
  const StudyOptions& o = session.options();
  render::Compositor& comp = frames.compositor();
  Gamepad pad;
  Phase phase = Phase::first;
  auto phase_start = Clock::now();
  bool drawn = false;  // the phase's frame is in the output framebuffer
  auto enter = [&](Phase p) {
    phase = p;
    phase_start = Clock::now();
    drawn = false;
    // The operator's console follows the run (and a test knows when to press).
    if (p == Phase::respond)
      std::fprintf(stderr, "study: trial %d of %zu: waiting for the answer\n", session.trial().index, session.planned());
    if (p == Phase::pause)
      std::fprintf(stderr, "study: pause after a failed validation trial (%d so far): Enter, Space or Start goes on\n",
                   session.validation_failures());
  };
  if (session.pause_requested()) enter(Phase::pause);
  while (!session.done()) {
    if (window.should_close()) return bad_input("study quit: the window was closed; nothing was written");
    const PlannedTrial& t = session.trial();
    if (!drawn) {
      // The scene is static: each presentation is rendered once and shown for its time.
      Status st = phase == Phase::first ? frames.draw(t, 0) : phase == Phase::second ? frames.draw(t, 1) : Status{};
      if (!st) return st;
      if (phase != Phase::first && phase != Phase::second) frames.draw_black();
      drawn = true;
    }
    window.present(frames.output_framebuffer(), comp.width(), comp.height());
    const double elapsed = seconds_since(phase_start);

    std::vector<std::optional<int>> responses;
    bool go_on = false;  // a key that ends the pause
    for (int key : window.take_keys()) {
      if (key == GLFW_KEY_ESCAPE) return bad_input("study quit (Esc); nothing was written");
      responses.push_back(key_response(key, o.design));
      go_on |= key == GLFW_KEY_ENTER || key == GLFW_KEY_SPACE;
    }
    for (int b : pad.pressed()) {
      responses.push_back(button_response(b, o.design));
      go_on |= b == GLFW_GAMEPAD_BUTTON_START || b == GLFW_GAMEPAD_BUTTON_A;
    }

    switch (phase) {
      case Phase::first:
        if (elapsed >= o.present_s) enter(o.blank_s > 0 ? Phase::blank : Phase::second);
        break;
      case Phase::blank:
        if (elapsed >= o.blank_s) enter(Phase::second);
        break;
      case Phase::second:
        if (elapsed >= o.present_s) enter(Phase::respond);
        break;
      case Phase::respond:
        // Presses during the presentations do not count; the first fitting one here does.
        for (const auto& r : responses) {
          if (!r) continue;
          if (Status st = session.respond({*r, elapsed}); !st) continue;  // 3-5 in a 2AFC trial
          enter(session.pause_requested() ? Phase::pause : Phase::first);
          break;
        }
        break;
      case Phase::pause:
        if (elapsed >= kStudyPauseMinS && go_on) {
          session.resume();
          enter(Phase::first);
        }
        break;
    }
  }
  return {};
}

}  // namespace foveal
