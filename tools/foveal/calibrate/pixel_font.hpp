#pragma once
// A 5×7 pixel font for instructions drawn into a frame a person sees in a headset, where
// the window title and the terminal are out of sight (foveal calibrate). Upper case,
// digits and common punctuation; lower case is drawn as upper case, anything else as a
// blank. Pure: no GL, no state.
#include <string_view>
#include <vector>

namespace foveal::cmd {

struct PixelRect {
  int x, y, w, h;  ///< bottom-left origin (GL's), pixels
};

constexpr int kGlyphW = 5, kGlyphH = 7, kGlyphAdvance = 6, kLineAdvance = 9;  ///< in font pixels

/// The lit cells of `text` as rectangles, each font pixel `scale`×`scale`, the first
/// line's top-left at (x, top). '\n' starts a new line.
std::vector<PixelRect> text_rects(std::string_view text, int x, int top, int scale);

/// Width in pixels of the longest line of `text` at `scale`.
int text_width(std::string_view text, int scale);

}  // namespace foveal::cmd
