#include "foveal/image/image.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>

#include "foveal/core/atomic_file.hpp"
#include "foveal/core/read_file.hpp"

namespace foveal::image {

namespace {

constexpr int kMaxSide = 65536;
constexpr std::size_t kMaxBytes = std::size_t{1} << 30;

Status check_header_size(const std::string& path, int w, int h) {
  if (w <= 0 || h <= 0 || w > kMaxSide || h > kMaxSide ||
      static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4 > kMaxBytes)
    return bad_input(path + ": " + std::to_string(w) + "×" + std::to_string(h) + " is larger than foveal reads (sides up to " +
                     std::to_string(kMaxSide) + ", at most " + describe_bytes(kMaxBytes) + " as RGBA8)");
  return {};
}

}  // namespace

Result<ImageHeader> probe(const std::string& path) {
  auto fd = open_regular_file(path, "image");
  if (!fd) return fd.error();
  struct Source {
    int fd;
    bool eof = false;
  } src{*fd};
  stbi_io_callbacks io{};
  io.read = [](void* u, char* data, int size) -> int {
    auto* s = static_cast<Source*>(u);
    for (;;) {
      const ssize_t n = ::read(s->fd, data, static_cast<std::size_t>(size));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) s->eof = true;
      return n > 0 ? static_cast<int>(n) : 0;
    }
  };
  io.skip = [](void* u, int n) { ::lseek(static_cast<Source*>(u)->fd, n, SEEK_CUR); };
  io.eof = [](void* u) -> int { return static_cast<Source*>(u)->eof ? 1 : 0; };
  int w = 0, h = 0, n = 0;
  const bool ok = stbi_info_from_callbacks(&io, &src, &w, &h, &n) != 0;
  struct stat st {};
  const bool sized = ::fstat(*fd, &st) == 0;
  ::close(*fd);
  if (!ok) {
    const char* why = stbi_failure_reason();
    return bad_input(path + ": cannot read image: " + (why ? why : "unknown error"));
  }
  if (Status s = check_header_size(path, w, h); !s) return s.error();
  return ImageHeader{w, h, sized ? static_cast<std::uint64_t>(st.st_size) : 0};
}

Result<Image> load(const std::string& path) {
  // The header's dimensions are checked before decoding: a few bytes can claim 10^10 pixels.
  auto bytes = read_regular_file(path, kMaxBytes, "image");
  if (!bytes) return bytes.error();
  if (bytes->size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) return bad_input(path + ": image file too large");
  const auto* data_in = reinterpret_cast<const stbi_uc*>(bytes->data());
  const int size = static_cast<int>(bytes->size());
  int w = 0, h = 0, n = 0;
  if (!stbi_info_from_memory(data_in, size, &w, &h, &n)) {
    const char* why = stbi_failure_reason();
    return bad_input(path + ": cannot read image: " + (why ? why : "unknown error"));
  }
  if (Status s = check_header_size(path, w, h); !s) return s.error();
  stbi_uc* data = stbi_load_from_memory(data_in, size, &w, &h, &n, 4);
  if (!data) {
    const char* why = stbi_failure_reason();
    // Memory short is not the file's fault: an internal error (exit 1), as a bad_alloc is.
    if (why && std::strcmp(why, "outofmem") == 0) return Error{ErrorKind::internal, path + ": out of memory decoding the image"};
    return bad_input(path + ": cannot read image: " + (why ? why : "unknown error"));
  }
  Image img(w, h);
  std::memcpy(img.rgba.data(), data, img.rgba.size());
  stbi_image_free(data);
  return img;
}

Status save_png(const std::string& path, const Image& img) {
  if (img.empty()) return bad_input(path + ": refusing to write an empty image");
  std::string bytes;
  auto sink = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(sink, &bytes, img.width, img.height, 4, img.rgba.data(), img.width * 4))
    return io_error(path + ": PNG encoding failed");
  return write_file_atomically(path, bytes);
}

Image crop(const Image& img, Rect r) {
  const int x0 = std::clamp(r.x, 0, img.width), y0 = std::clamp(r.y, 0, img.height);
  const int x1 = std::clamp(r.x + r.w, 0, img.width), y1 = std::clamp(r.y + r.h, 0, img.height);
  Image out(x1 - x0, y1 - y0);
  for (int y = y0; y < y1; ++y) std::memcpy(out.at(0, y - y0), img.at(x0, y), static_cast<std::size_t>(x1 - x0) * 4);
  return out;
}

Image hconcat(const Image& left, const Image& right) {
  Image out(left.width + right.width, std::max(left.height, right.height));
  for (int y = 0; y < left.height; ++y) std::memcpy(out.at(0, y), left.at(0, y), static_cast<std::size_t>(left.width) * 4);
  for (int y = 0; y < right.height; ++y)
    std::memcpy(out.at(left.width, y), right.at(0, y), static_cast<std::size_t>(right.width) * 4);
  return out;
}

double psnr(const Image& a, const Image& b) { return psnr(a, b, Rect{0, 0, a.width, a.height}); }

double psnr(const Image& a, const Image& b, Rect r) {
  if (a.width != b.width || a.height != b.height) return std::numeric_limits<double>::quiet_NaN();
  const int x0 = std::max(r.x, 0), y0 = std::max(r.y, 0);
  const int x1 = std::min(r.x + r.w, a.width), y1 = std::min(r.y + r.h, a.height);
  double sum = 0;
  std::size_t n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t *p = a.at(x, y), *q = b.at(x, y);
      for (int c = 0; c < 3; ++c) {
        const double d = double(p[c]) - double(q[c]);
        sum += d * d;
      }
      n += 3;
    }
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  if (sum == 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(255.0 * 255.0 / (sum / double(n)));
}

int max_abs_diff(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) return 255;
  int m = 0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    if (i % 4 != 3) m = std::max(m, std::abs(int(a.rgba[i]) - int(b.rgba[i])));
  return m;
}

Image diff_image(const Image& a, const Image& b, int gain) {
  Image out(a.width, a.height);
  if (a.width != b.width || a.height != b.height) return out;
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    out.rgba[i] = i % 4 == 3 ? 255 : static_cast<std::uint8_t>(std::min(255, gain * std::abs(int(a.rgba[i]) - int(b.rgba[i]))));
  return out;
}

}  // namespace foveal::image
