// The 5x7 font that writes calibrate's instructions into the headset's picture.
#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "calibrate/pixel_font.hpp"

namespace foveal::cmd {
namespace {

/// The lit font pixels of `text` at scale 1, as (column, row from the top) pairs.
std::set<std::pair<int, int>> cells(std::string_view text) {
  std::set<std::pair<int, int>> out;
  for (const PixelRect& r : text_rects(text, 0, 0, 1)) {
    EXPECT_EQ(r.w, 1);
    out.insert({r.x, -r.y - 1});
  }
  return out;
}

TEST(PixelFont, GlyphsSitOnTheirGridAndScale) {
  // "L": the left column and the bottom row.
  const auto l = cells("L");
  EXPECT_EQ(l.size(), 7u + 4u);
  for (int row = 0; row < kGlyphH; ++row) EXPECT_TRUE(l.count({0, row})) << row;
  for (int col = 0; col < kGlyphW; ++col) EXPECT_TRUE(l.count({col, kGlyphH - 1})) << col;
  // Scaled: each cell is scale x scale, placed from the top-left given, GL's y up.
  const auto big = text_rects("L", 100, 500, 3);
  ASSERT_EQ(big.size(), l.size());
  EXPECT_EQ(big.front().x, 100);
  EXPECT_EQ(big.front().y, 500 - 3);
  EXPECT_EQ(big.front().w, 3);
}

TEST(PixelFont, LowerCaseIsUpperCaseUnknownIsBlankAndLinesAdvance) {
  EXPECT_EQ(cells("same"), cells("SAME"));
  EXPECT_TRUE(cells("\x01").empty());
  EXPECT_TRUE(cells(" ").empty());
  // A second character starts kGlyphAdvance to the right; a second line kLineAdvance down.
  for (auto [x, y] : cells(" L")) EXPECT_GE(x, kGlyphAdvance);
  for (auto [x, y] : cells("\nL")) EXPECT_GE(y, kLineAdvance);
  EXPECT_EQ(text_width("AB\nC", 2), (2 * kGlyphAdvance - 1) * 2);
  EXPECT_EQ(text_width("", 2), 0);
}

TEST(PixelFont, EveryCharacterOfTheInstructionsIsDrawn) {
  // The calibration's questions and keys use these: none may fall back to a blank.
  const std::string used = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789.,:;?!-+=/()'<>";
  for (char c : used) EXPECT_FALSE(cells(std::string(1, c)).empty()) << c;
}

}  // namespace
}  // namespace foveal::cmd
