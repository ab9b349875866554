#include "foveal/perception/pyramid.hpp"

#include <algorithm>

namespace foveal::perception {

namespace {

constexpr float kK[5] = {0.05f, 0.25f, 0.4f, 0.25f, 0.05f};

inline int mirror(int i, int n) {
  if (i < 0) return std::min(-i - 1, n - 1);
  if (i >= n) return std::max(2 * n - 1 - i, 0);
  return i;
}

// One row of the reduce step along x: out[m] = Σ k[j] in[2m + j - 2].
void reduce_row(const float* in, int n, float* out, int m_out) {
  for (int m = 0; m < m_out; ++m) {
    const int c = 2 * m;
    float s;
    if (c >= 2 && c + 2 < n) {
      s = kK[0] * in[c - 2] + kK[1] * in[c - 1] + kK[2] * in[c] + kK[3] * in[c + 1] + kK[4] * in[c + 2];
    } else {
      s = 0;
      for (int j = 0; j < 5; ++j) s += kK[j] * in[mirror(c + j - 2, n)];
    }
    out[m] = s;
  }
}

// One row of the expand step along x: even outputs 0.1, 0.8, 0.1 of three coarse samples,
// odd outputs the mean of two.
void expand_row(const float* in, int n, float* out, int w) {
  const auto at = [&](int i) { return in[std::min(std::max(i, 0), n - 1)]; };
  for (int p = 0; p < w; ++p) {
    const int m = p >> 1;
    out[p] = (p & 1) ? 0.5f * (at(m) + at(m + 1)) : 0.1f * at(m - 1) + 0.8f * at(m) + 0.1f * at(m + 1);
  }
}

}  // namespace

Plane pyramid_reduce(const Plane& in) {
  const int w2 = (in.width + 1) / 2, h2 = (in.height + 1) / 2;
  Plane tmp(w2, in.height), out(w2, h2);
  for (int y = 0; y < in.height; ++y) reduce_row(in.row(y), in.width, tmp.row(y), w2);
  std::vector<const float*> rows(5);
  for (int m = 0; m < h2; ++m) {
    for (int j = 0; j < 5; ++j) rows[static_cast<std::size_t>(j)] = tmp.row(mirror(2 * m + j - 2, in.height));
    float* o = out.row(m);
    for (int x = 0; x < w2; ++x)
      o[x] = kK[0] * rows[0][x] + kK[1] * rows[1][x] + kK[2] * rows[2][x] + kK[3] * rows[3][x] + kK[4] * rows[4][x];
  }
  return out;
}

Plane pyramid_expand(const Plane& coarse, int w, int h) {
  Plane tmp(w, coarse.height), out(w, h);
  for (int y = 0; y < coarse.height; ++y) expand_row(coarse.row(y), coarse.width, tmp.row(y), w);
  const auto row = [&](int i) { return tmp.row(std::min(std::max(i, 0), coarse.height - 1)); };
  for (int p = 0; p < h; ++p) {
    const int m = p >> 1;
    float* o = out.row(p);
    if (p & 1) {
      const float *a = row(m), *b = row(m + 1);
      for (int x = 0; x < w; ++x) o[x] = 0.5f * (a[x] + b[x]);
    } else {
      const float *a = row(m - 1), *b = row(m), *c = row(m + 1);
      for (int x = 0; x < w; ++x) o[x] = 0.1f * a[x] + 0.8f * b[x] + 0.1f * c[x];
    }
  }
  return out;
}

}  // namespace foveal::perception
