#pragma once
// 8-bit RGBA images on the CPU: PNG in and out, and the comparisons the tests need.
// Rows run top to bottom (row 0 is the top of the picture), 4 bytes per pixel.
#include <cstdint>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"

namespace foveal::image {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  ///< width * height * 4 bytes

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4, 0) {}
  std::uint8_t* at(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4]; }
  const std::uint8_t* at(int x, int y) const { return &rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4]; }
  bool empty() const { return width <= 0 || height <= 0; }
};

/// Pixel rectangle [x, x+w) × [y, y+h), top-left origin.
struct Rect {
  int x = 0, y = 0, w = 0, h = 0;
};

/// Loads PNG, JPEG, BMP, TGA (stb_image) as RGBA8. Errors name the file and the reason.
Result<Image> load(const std::string& path);
/// What a file's header says, read without decoding it: for sizing the work before any.
struct ImageHeader {
  int width = 0, height = 0;
  std::uint64_t file_bytes = 0;
};
/// The header of an image load() would read (same checks: regular file, sizes foveal reads).
Result<ImageHeader> probe(const std::string& path);
/// Writes a PNG atomically (temporary file + rename).
Status save_png(const std::string& path, const Image& img);

/// The part of `img` inside `r` (clipped to the image).
Image crop(const Image& img, Rect r);
/// Side by side: `left` then `right` (same height).
Image hconcat(const Image& left, const Image& right);

/// PSNR in dB over the R, G and B channels (alpha ignored) of two images of the same
/// size, optionally only inside `r`: 10·log10(255² / MSE) with MSE averaged over the
/// three channels. Identical images give +infinity.
double psnr(const Image& a, const Image& b);
double psnr(const Image& a, const Image& b, Rect r);
/// Largest absolute difference of any R, G, B value.
int max_abs_diff(const Image& a, const Image& b);
/// |a - b| per channel, scaled by `gain` and clamped, alpha opaque: for looking at.
Image diff_image(const Image& a, const Image& b, int gain = 8);

}  // namespace foveal::image
