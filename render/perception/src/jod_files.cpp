#include "foveal/perception/jod_files.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "foveal/core/read_file.hpp"
#include "foveal/image/image.hpp"

namespace foveal::perception {

namespace fs = std::filesystem;

namespace {

bool is_image_name(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e == ".png" || e == ".jpg" || e == ".jpeg" || e == ".bmp" || e == ".tga";
}

// The non-empty, non-comment lines of a list file, numbered from 1, read through the
// project's file entry point: a FIFO, a device or a file past kMaxListBytes is refused
// before anything is read (a link to /dev/zero once grew one "line" to a gigabyte).
Result<std::vector<std::pair<int, std::string>>> list_lines(const std::string& path, const std::string& what) {
  auto text = read_regular_file(path, kMaxListBytes, what);
  if (!text) return text.error();
  std::vector<std::pair<int, std::string>> out;
  std::istringstream in(*text);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    out.emplace_back(n, std::move(line));
  }
  return out;
}

Result<std::vector<std::array<std::optional<NormFovea>, 2>>> read_fovea_list(const std::string& path) {
  auto lines = list_lines(path, "fovea list");
  if (!lines) return Error{lines.error().kind, "--fovea-list " + lines.error().message};
  std::vector<std::array<std::optional<NormFovea>, 2>> out;
  for (const auto& [n, line] : *lines) {
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
        return bad_input(where + "'" + cell.substr(0, 40) + "' is not a number in [0,1]");
      v.push_back(d);
      if (v.size() > 4) break;
    }
    if (v.size() != 2 && v.size() != 4)
      return bad_input(where + "need X,Y or XL,YL,XR,YR (or none), got '" + line.substr(0, 80) + (line.size() > 80 ? "...'" : "'"));
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
    auto lines = list_lines(path, "frame list");
    if (!lines) return Error{lines.error().kind, std::string(what) + " " + lines.error().message};
    std::vector<std::string> out;
    for (const auto& [n, line] : *lines) {
      const fs::path p(line);
      out.push_back(p.is_absolute() ? line : (fs::path(path).parent_path() / p).string());
    }
    if (out.empty()) return bad_input(std::string(what) + " " + path + ": the frame list is empty");
    return out;
  }
  return std::vector<std::string>{path};
}

std::uint64_t jod_working_set_bytes(int eye_width, int eye_height, int eyes, std::size_t frames, double fps,
                                    std::uint64_t file_bytes) {
  // Bytes per eye pixel (float planes, 4 B; a pyramid is 4/3 of its base), from jod.cpp:
  const double px = static_cast<double>(eye_width) * static_cast<double>(eye_height);
  const double full = px * eyes;                   // a whole (side-by-side) frame
  const bool video = frames > 1;
  // The ring's slots are filled as frames come: a short video holds only its frames.
  const double ring = video ? std::min(std::ceil(std::clamp(fps, 0.0, 1e6) / 4.0), static_cast<double>(frames)) : 0.0;
  const double held = eyes * (16.0 / 3 + 8.0 * ring);  // per eye: band geometry, the video's ring
  // One frame's work, an eye at a time: luminance (still) or 4 channels (video), their
  // Gaussian pyramids, the band being expanded.
  const double work = video ? 16.0 + 4 * 16.0 / 3 + 20.0 : 8.0 + 2 * 16.0 / 3 + 10.0;
  const double scoring = 8.0 * full + (eyes > 1 ? 8.0 * px : 0.0) + work * px;  // both frames decoded, stereo crops
  // Decoding the test frame beside the reference: the file, stb_image's inflated data and
  // its output, and our copy (~2 file sizes + 8 B a pixel over the reference's 4).
  const double decoding = 12.0 * full + 2.0 * static_cast<double>(file_bytes);
  return static_cast<std::uint64_t>(held * px + std::max(scoring, decoding));
}

Result<JodPlan> plan_jod(const JodRequest& rq) {
  JodPlan plan;
  auto refs = frame_paths(rq.reference, "--ref");
  if (!refs) return refs.error();
  auto tests = frame_paths(rq.test, "--test");
  if (!tests) return tests.error();
  if (refs->size() != tests->size())
    return bad_input("--test: " + std::to_string(tests->size()) + " frames, the reference has " + std::to_string(refs->size()));
  const std::size_t n = refs->size();
  if (n > 1 && !(rq.fps > 0)) return bad_input("--fps: needed for " + std::to_string(n) + " frames (and > 0)");
  // The headers only: the work is sized before a pixel is decoded.
  auto ref = image::probe(refs->front());
  if (!ref) return bad_input("--ref " + ref.error().message);
  auto test = image::probe(tests->front());
  if (!test) return bad_input("--test " + test.error().message);
  if (ref->width != test->width || ref->height != test->height)
    return bad_input(tests->front() + ": size " + std::to_string(test->width) + "x" + std::to_string(test->height) +
                     " differs from the reference " + refs->front() + " (" + std::to_string(ref->width) + "x" +
                     std::to_string(ref->height) + ")");
  plan.eyes = rq.stereo ? 2 : 1;
  if (rq.stereo && ref->width % 2 != 0) return bad_input(refs->front() + ": a stereo frame needs an even width");
  plan.width = ref->width / plan.eyes;
  plan.height = ref->height;
  if (plan.width < 8 || plan.height < 8) return bad_input(refs->front() + ": an eye's image of at least 8x8 is needed");
  plan.bytes = jod_working_set_bytes(plan.width, plan.height, plan.eyes, n, rq.fps, std::max(ref->file_bytes, test->file_bytes));
  plan.refs = std::move(*refs);
  plan.tests = std::move(*tests);
  return plan;
}

Result<JodReport> run_jod(const JodRequest& rq) {
  if (auto s = rq.photometry.validate(); !s) return s.error();
  auto planned = plan_jod(rq);
  if (!planned) return planned.error();
  const std::vector<std::string>& refs = planned->refs;
  const std::vector<std::string>& tests = planned->tests;
  const std::size_t n = refs.size();
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
    // Each frame's header before its pixels: a later frame of another size is refused
    // before it is decoded (the plan sized the work from the first).
    for (const auto* frame : {&refs[f], &tests[f]}) {
      auto hd = image::probe(*frame);
      if (!hd) return bad_input(std::string(frame == &refs[f] ? "--ref " : "--test ") + hd.error().message);
      if (hd->width != planned->width * n_eyes || hd->height != planned->height)
        return bad_input(*frame + ": size " + std::to_string(hd->width) + "x" + std::to_string(hd->height) + " differs from " +
                         refs.front() + " (" + std::to_string(planned->width * n_eyes) + "x" + std::to_string(planned->height) + ")");
    }
    auto ref = load_frame(refs[f]);
    if (!ref) return Error{ref.error().kind, "--ref " + ref.error().message};
    auto test = load_frame(tests[f]);
    if (!test) return Error{test.error().kind, "--test " + test.error().message};
    if (ref->width != test->width || ref->height != test->height ||
        ref->width != planned->width * n_eyes || ref->height != planned->height)
      return bad_input(tests[f] + ": size " + std::to_string(test->width) + "x" + std::to_string(test->height) +
                       " differs from the reference " + refs[f] + " (" + std::to_string(ref->width) + "x" +
                       std::to_string(ref->height) + ") or the first frame");
    const int w = planned->width, h = planned->height;
    if (f == 0) {
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
    }
    for (int e = 0; e < n_eyes; ++e) {
      // Mono frames are scored in place; a stereo eye is a crop (counted in the plan).
      image::Image r_eye, t_eye;
      if (rq.stereo) r_eye = image::crop(*ref, {e * w, 0, w, h}), t_eye = image::crop(*test, {e * w, 0, w, h});
      const image::Image& r = rq.stereo ? r_eye : *ref;
      const image::Image& t = rq.stereo ? t_eye : *test;
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
