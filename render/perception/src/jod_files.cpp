#include "foveal/perception/jod_files.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "foveal/image/image.hpp"

namespace foveal::perception {

namespace fs = std::filesystem;

namespace {

bool is_image_name(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e == ".png" || e == ".jpg" || e == ".jpeg" || e == ".bmp" || e == ".tga";
}

Result<std::vector<std::array<std::optional<NormFovea>, 2>>> read_fovea_list(const std::string& path) {
  std::ifstream in(path);
  if (!in) return bad_input(path + ": cannot read the fovea list");
  std::vector<std::array<std::optional<NormFovea>, 2>> out;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    const std::string where = path + ":" + std::to_string(n) + ": ";
    if (line == "none") {
      out.push_back({});
      continue;
    }
    std::vector<double> v;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) {
      char* end = nullptr;
      const double d = std::strtod(cell.c_str(), &end);
      if (cell.empty() || end != cell.c_str() + cell.size() || !std::isfinite(d) || d < 0 || d > 1)
        return bad_input(where + "'" + cell + "' is not a number in [0,1]");
      v.push_back(d);
    }
    if (v.size() != 2 && v.size() != 4) return bad_input(where + "need X,Y or XL,YL,XR,YR (or none), got '" + line + "'");
    NormFovea l{v[0], v[1]}, r = v.size() == 4 ? NormFovea{v[2], v[3]} : l;
    out.push_back({l, r});
  }
  return out;
}

Result<image::Image> load_frame(const std::string& path) {
  auto img = image::load(path);
  if (!img) return img.error();
  return img;
}

}  // namespace

Result<std::vector<std::string>> frame_paths(const std::string& path, const char* what) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(path, ec))
      if (e.is_regular_file() && is_image_name(e.path())) out.push_back(e.path().string());
    if (ec) return bad_input(std::string(what) + " " + path + ": " + ec.message());
    std::sort(out.begin(), out.end());
    if (out.empty()) return bad_input(std::string(what) + " " + path + ": no image files (png, jpg, bmp, tga) in the folder");
    return out;
  }
  if (fs::path(path).extension() == ".txt") {
    std::ifstream in(path);
    if (!in) return bad_input(std::string(what) + " " + path + ": cannot read the frame list");
    std::vector<std::string> out;
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      const fs::path p(line);
      out.push_back(p.is_absolute() ? line : (fs::path(path).parent_path() / p).string());
    }
    if (out.empty()) return bad_input(std::string(what) + " " + path + ": the frame list is empty");
    return out;
  }
  return std::vector<std::string>{path};
}

Result<JodReport> run_jod(const JodRequest& rq) {
  if (auto s = rq.photometry.validate(); !s) return s.error();
  auto refs = frame_paths(rq.reference, "--ref");
  if (!refs) return refs.error();
  auto tests = frame_paths(rq.test, "--test");
  if (!tests) return tests.error();
  if (refs->size() != tests->size())
    return bad_input("--test: " + std::to_string(tests->size()) + " frames, the reference has " + std::to_string(refs->size()));
  const std::size_t n = refs->size();
  if (n > 1 && !(rq.fps > 0)) return bad_input("--fps: needed for " + std::to_string(n) + " frames (and > 0)");
  std::vector<std::array<std::optional<NormFovea>, 2>> fovea(n, {rq.fovea_left, rq.stereo ? rq.fovea_right : rq.fovea_left});
  if (!rq.fovea_list.empty()) {
    auto l = read_fovea_list(rq.fovea_list);
    if (!l) return l.error();
    if (l->size() != n)
      return bad_input(rq.fovea_list + ": " + std::to_string(l->size()) + " foveae for " + std::to_string(n) + " frames");
    fovea = std::move(*l);
  }
  const int n_eyes = rq.stereo ? 2 : 1;
  std::vector<JodMetric> metrics;
  std::vector<JodMetric::Video> videos;
  JodReport report;
  for (std::size_t f = 0; f < n; ++f) {
    auto ref = load_frame((*refs)[f]);
    if (!ref) return bad_input("--ref " + ref.error().message);
    auto test = load_frame((*tests)[f]);
    if (!test) return bad_input("--test " + test.error().message);
    if (ref->width != test->width || ref->height != test->height)
      return bad_input((*tests)[f] + ": size " + std::to_string(test->width) + "x" + std::to_string(test->height) +
                       " differs from the reference " + (*refs)[f] + " (" + std::to_string(ref->width) + "x" +
                       std::to_string(ref->height) + ")");
    if (rq.stereo && ref->width % 2 != 0) return bad_input((*refs)[f] + ": a stereo frame needs an even width");
    const int w = ref->width / n_eyes, h = ref->height;
    if (f == 0) {
      if (w < 8 || h < 8) return bad_input((*refs)[f] + ": an eye's image of at least 8x8 is needed");
      report.width = w;
      report.height = h;
      for (int e = 0; e < n_eyes; ++e) {
        metrics.emplace_back(eye_geometry(rq.display, e == 0 ? Eye::left : Eye::right, w, h), rq.photometry, rq.parameters, rq.threads);
        if (n > 1) {
          auto v = metrics.back().video(rq.fps);
          if (!v) return v.error();
          videos.push_back(std::move(*v));
        }
      }
    } else if (w != report.width || h != report.height) {
      return bad_input((*refs)[f] + ": frame size differs from the first frame's");
    }
    for (int e = 0; e < n_eyes; ++e) {
      const image::Image r = rq.stereo ? image::crop(*ref, {e * w, 0, w, h}) : *ref;
      const image::Image t = rq.stereo ? image::crop(*test, {e * w, 0, w, h}) : *test;
      std::optional<Fixation> fix;
      if (const auto& fv = fovea[f][static_cast<std::size_t>(e)]) fix = Fixation{fv->x * w, fv->y * h};
      if (n == 1) {
        auto s = metrics[static_cast<std::size_t>(e)].still(r, t, fix);
        if (!s) return s.error();
        report.eyes.push_back(*s);
      } else if (auto s = videos[static_cast<std::size_t>(e)].push(r, t, fix); !s) {
        return s.error();
      }
    }
  }
  if (n > 1)
    for (auto& v : videos) {
      auto s = v.score();
      if (!s) return s.error();
      report.eyes.push_back(*s);
    }
  report.combined = report.eyes[0];
  if (n_eyes == 2) {
    report.combined.q = 0.5 * (report.eyes[0].q + report.eyes[1].q);
    report.combined.jod = jod_from_q(report.combined.q, rq.parameters);
  }
  return report;
}

}  // namespace foveal::perception
