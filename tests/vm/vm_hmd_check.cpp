#include "vm_hmd_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include <glm/vec2.hpp>

#include "hmd_motion.hpp"
#include "vive_pattern.hpp"

namespace foveal::vmtest {
namespace {

constexpr double kDeg = M_PI / 180.0;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, ',')) out.push_back(f);
  return out;
}

glm::dvec3 forward(const glm::dquat& q) { return q * glm::dvec3(0, 0, -1); }
/// Heading about the vertical: 0 facing -z, positive turning towards -x (a positive yaw about +y).
double heading(const glm::dquat& q) {
  const glm::dvec3 f = forward(q);
  return std::atan2(-f.x, -f.z);
}
double pitch(const glm::dquat& q) { return std::asin(std::clamp(forward(q).y, -1.0, 1.0)); }
double roll(const glm::dquat& q) { return std::asin(std::clamp((q * glm::dvec3(1, 0, 0)).y, -1.0, 1.0)); }
/// The angle of the rotation from a to b (from the vector part: acos near 1 loses digits).
double angle_between(const glm::dquat& a, const glm::dquat& b) {
  const glm::dquat d = glm::conjugate(a) * b;
  return 2 * std::asin(std::min(1.0, glm::length(glm::dvec3(d.x, d.y, d.z))));
}

glm::dquat dq(const Pose& p) { return glm::dquat(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z); }
TimeNs ref_time(const HeadRow& r) { return r.pose_t_ns ? r.pose_t_ns : r.t_ns; }
bool in(const std::vector<Window>& ws, TimeNs t) {
  return std::any_of(ws.begin(), ws.end(), [&](const Window& w) { return t >= w.from && t <= w.to; });
}
/// No pose yet: the frame shows the scene's own view (the identity).
bool has_pose(const HeadRow& r) { return !(r.pose == Pose{}); }

}  // namespace

std::vector<HeadRow> read_head_rows(const std::string& path, std::string& problem) {
  std::vector<HeadRow> rows;
  std::ifstream f(path);
  std::string line;
  if (!std::getline(f, line)) {
    problem = path + ": empty or missing";
    return rows;
  }
  std::map<std::string, std::size_t> col;
  const auto names = split(line);
  for (std::size_t i = 0; i < names.size(); ++i) col[names[i]] = i;
  for (const char* need : {"frame", "t_ns", "head_x", "head_y", "head_z", "head_qw", "head_qx", "head_qy", "head_qz"})
    if (!col.count(need)) {
      problem = path + ": no column " + need;
      return rows;
    }
  const bool has_pose_time = col.count("head_t_ns") > 0;
  while (std::getline(f, line)) {
    const auto v = split(line);
    if (v.size() < names.size()) continue;  // a row being written
    HeadRow r;
    r.frame = std::stoull(v[col["frame"]]);
    r.t_ns = std::stoll(v[col["t_ns"]]);
    if (has_pose_time) r.pose_t_ns = std::stoll(v[col["head_t_ns"]]);
    r.pose.position_m = {std::stof(v[col["head_x"]]), std::stof(v[col["head_y"]]), std::stof(v[col["head_z"]])};
    r.pose.orientation = glm::quat(std::stof(v[col["head_qw"]]), std::stof(v[col["head_qx"]]), std::stof(v[col["head_qy"]]),
                                   std::stof(v[col["head_qz"]]));
    rows.push_back(r);
  }
  return rows;
}

std::string describe_rows(const std::vector<HeadRow>& rows) {
  std::string out;
  for (const HeadRow& r : rows) {
    const glm::dquat q = dq(r.pose);
    char b[200];
    std::snprintf(b, sizeof b, "  frame %llu t=%.3f head_t=%.3f pos=(%.4f %.4f %.4f) heading=%.4f pitch=%.4f roll=%.4f\n",
                  static_cast<unsigned long long>(r.frame), seconds(r.t_ns), seconds(r.pose_t_ns), r.pose.position_m.x,
                  r.pose.position_m.y, r.pose.position_m.z, heading(q), pitch(q), roll(q));
    out += b;
  }
  return out;
}

std::string FollowCheck::summary() const {
  char b[300];
  std::snprintf(b, sizeof b, "rows=%zu checked=%zu bad=%zu max_pos_m=%.4f max_angle_deg=%.2f max_time_s=%.3f rate=%.4f %s",
                rows, checked, bad, max_position_m, max_angle_deg, max_time_s, rate, problem.c_str());
  return b;
}

FollowCheck check_psvr2_rows(const std::vector<HeadRow>& rows, const std::vector<Window>& windows) {
  FollowCheck c;
  c.rows = rows.size();
  const double w = kPsvr2YawRate;
  const bool timed = !rows.empty() && rows.front().pose_t_ns != 0;
  std::vector<double> lags;
  const double late_tol = timed ? kPsvr2LateTolS : 1.5, early_tol = timed ? kPsvr2EarlyTolS : 1.5;
  for (const HeadRow& r : rows) {
    if (!has_pose(r) || !in(windows, ref_time(r))) continue;
    ++c.checked;
    const glm::dquat q = dq(r.pose);
    const double t_ref = seconds(ref_time(r)), h = heading(q);
    const double turns = std::round((w * t_ref - h) / (2 * M_PI));
    const double t = (h + 2 * M_PI * turns) / w;
    const HeadMotion m = psvr2_motion(static_cast<TimeNs>(t * 1e9));
    const double dp = glm::length(glm::dvec3(r.pose.position_m) - m.position_m);
    const double da = angle_between(q, m.orientation) / kDeg, dt = t - t_ref;
    c.max_position_m = std::max(c.max_position_m, dp);
    c.max_angle_deg = std::max(c.max_angle_deg, da);
    c.max_time_s = std::max(c.max_time_s, std::abs(dt));
    lags.push_back(-dt);
    if (dp > kPositionTolM || da > kAngleTolDeg || dt < -late_tol || dt > early_tol) {
      if (c.bad++ == 0) {
        char b[200];
        std::snprintf(b, sizeof b, "first bad: frame %llu pos_err=%.4f angle_err=%.2f time_err=%+.3f",
                      static_cast<unsigned long long>(r.frame), dp, da, dt);
        c.problem = b;
      }
    }
  }
  if (!lags.empty()) {
    std::sort(lags.begin(), lags.end());
    char b[80];
    std::snprintf(b, sizeof b, " lag p50 %.3f s max %.3f s", lags[lags.size() / 2], lags.back());
    c.problem += b;
  }
  return c;
}

FollowCheck check_vive_rows(const std::vector<HeadRow>& rows, const std::vector<Window>& windows) {
  FollowCheck c;
  c.rows = rows.size();
  double worst_rate = 0;
  for (const Window& win : windows) {
    // Heading (unwrapped) against time, fitted by a line.
    std::vector<std::pair<double, double>> pts;
    const HeadRow* prev = nullptr;
    for (const HeadRow& r : rows) {
      const HeadRow* before = prev;
      prev = &r;
      if (!has_pose(r) || ref_time(r) < win.from || ref_time(r) > win.to) continue;
      ++c.checked;
      // A pose repeated from the frame before was held (nothing new for 100 ms): checked
      // for pitch and roll, left out of the heading's line.
      const bool repeated = before && before->pose == r.pose;
      const glm::dquat q = dq(r.pose);
      const double dpitch = std::abs(pitch(q) - kVivePitch) / kDeg, droll = std::abs(roll(q)) / kDeg;
      c.max_angle_deg = std::max({c.max_angle_deg, dpitch, droll});
      if (dpitch > kAngleTolDeg || droll > kAngleTolDeg) {
        if (c.bad++ == 0) {
          char b[160];
          std::snprintf(b, sizeof b, "first bad: frame %llu pitch_err=%.2f roll_err=%.2f deg ",
                        static_cast<unsigned long long>(r.frame), dpitch, droll);
          c.problem += b;
        }
      }
      if (repeated) continue;
      // Unwrapped towards where the motion's rate would have taken the previous heading,
      // so that frames seconds apart keep their turns.
      double h = heading(q);
      const double t = seconds(ref_time(r));
      if (!pts.empty()) {
        const double expect = pts.back().second + kViveYawRate * (t - pts.back().first);
        h += 2 * M_PI * std::round((expect - h) / (2 * M_PI));
      }
      pts.emplace_back(t, h);
    }
    if (pts.size() < 3 || pts.back().first - pts.front().first < 2.0) {
      c.problem += "a window has fewer than 3 poses over 2 s ";
      ++c.bad;
      continue;
    }
    double st = 0, sh = 0, stt = 0, sth = 0;
    const double n = static_cast<double>(pts.size()), t0 = pts.front().first;
    for (auto [t, h] : pts) {
      st += t - t0, sh += h, stt += (t - t0) * (t - t0), sth += (t - t0) * h;
    }
    const double slope = (n * sth - st * sh) / (n * stt - st * st);
    // The line's offset is the median pose's, not the least-squares one: poses that came
    // late (a loaded host delays the emulated sensor's reports) would pull a mean back and
    // make the timely ones look ahead by what they pulled.
    std::vector<double> offsets;
    for (auto [t, h] : pts) offsets.push_back(h - slope * (t - t0));
    std::nth_element(offsets.begin(), offsets.begin() + static_cast<std::ptrdiff_t>(offsets.size() / 2), offsets.end());
    const double icpt = offsets[offsets.size() / 2];
    // Residuals: ahead of the line by at most the angle tolerance (prediction
    // overshooting), behind by at most the late tolerance's worth of turning (late or
    // held measurements, as for the PS VR2).
    double max_res = 0, max_behind = 0;
    for (auto [t, h] : pts) {
      const double res = (h - (icpt + slope * (t - t0))) / kDeg;
      max_res = std::max(max_res, res);
      max_behind = std::max(max_behind, -res);
    }
    c.max_angle_deg = std::max(c.max_angle_deg, max_res);
    if (worst_rate == 0 || std::abs(slope - kViveYawRate) > std::abs(worst_rate - kViveYawRate)) worst_rate = slope;
    const double behind_tol = kViveYawRate * kPsvr2LateTolS / kDeg;
    if (std::abs(slope - kViveYawRate) > kViveRateTol * kViveYawRate || max_res > kAngleTolDeg || max_behind > behind_tol) {
      ++c.bad;
      char b[200];
      std::snprintf(b, sizeof b, "window of %zu poses: yaw rate %.4f rad/s (motion %.4f), up to %.2f deg ahead of the line, %.2f behind ",
                    pts.size(), slope, kViveYawRate, max_res, max_behind);
      c.problem += b;
    }
  }
  c.rate = worst_rate;
  return c;
}

ModelCheck check_vive_model(const nlohmann::json& m) {
  const ViveConfig& c = vive_config();
  std::string why;
  auto num = [&](const char* pointer) {
    const nlohmann::json::json_pointer p(pointer);
    if (!m.is_object() || !m.contains(p) || !m.at(p).is_number()) {
      why += std::string("no number at ") + pointer + "; ";
      return std::nan("");
    }
    return m.at(p).get<double>();
  };
  auto near = [&](const char* what, double got, double want, double tol) {
    if (!(std::abs(got - want) <= tol)) {
      char b[160];
      std::snprintf(b, sizeof b, "%s %.6g, the config says %.6g; ", what, got, want);
      why += b;
    }
  };
  near("eye_width", num("/eye_width"), c.eye_width, 0);
  near("eye_height", num("/eye_height"), c.eye_height, 0);
  near("ipd_mm", num("/ipd_mm"), c.lens_separation_m * 1000, 1e-3);
  double rms[2] = {0, 0}, worst[2] = {0, 0};
  for (int e = 0; e < 2; ++e) {
    const std::string side = e ? "right" : "left";
    // The configuration's view (Monado's reading): the frustum of the intrinsics
    // (normalised by half the eye's size) grown by grow_for_undistort, and where
    // channel ch of panel point p (origin top-left) samples that image (DISTORT_DPOLY3).
    const double grow = 1 + c.grow_for_undistort, fx = c.fx / grow, fy = c.fy / grow, cx = c.cx[e] / grow, cy = c.cy / grow;
    const double tan_l = -(1 - cx) / fx, tan_r = (1 + cx) / fx, tan_b = -(1 - cy) / fy, tan_t = (1 + cy) / fy;
    const double a = c.aspect_x_over_y, f = 0.5 / grow;
    // The model's: its frustum and its polynomial (docs/display-model.md).
    const std::string t = "/" + side + "/tangents/", d = "/distortion/" + side + "/";
    const double m_l = num((t + "left").c_str()), m_r = num((t + "right").c_str()), m_b = num((t + "bottom").c_str()),
                 m_t = num((t + "top").c_str());
    const glm::dvec2 centre(num((d + "center/0").c_str()), num((d + "center/1").c_str()));
    const double k1 = num((d + "k/0").c_str()), k2 = num((d + "k/1").c_str()), k3 = num((d + "k/2").c_str());
    const double scale[3] = {num((d + "channel_scale/0").c_str()), num((d + "channel_scale/1").c_str()),
                             num((d + "channel_scale/2").c_str())};
    const glm::dvec2 span(m_r - m_l, m_t - m_b);
    // Compared: the direction (tangents) each panel point shows in each channel, which
    // does not depend on how either side splits it into frustum and polynomial; the
    // error in the model's rendered pixels.
    double sum = 0;
    int n = 0;
    for (int i = 0; i <= 40; ++i)
      for (int j = 0; j <= 40; ++j) {
        const glm::dvec2 p(i / 40.0, j / 40.0);
        const double x = 2 * p.x - 1 - c.center_x[e], y = (2 * p.y - 1) / a - c.center_y, r2 = x * x + y * y;
        if (r2 > c.undistort_r2_cutoff) continue;
        for (int ch = 0; ch < 3; ++ch) {
          const double* k = c.coeffs[ch];
          const double s = 1 / (1 + r2 * (k[0] + r2 * (k[1] + r2 * k[2])));
          const glm::dvec2 src(0.5 + (x * s + c.center_x[e]) * f, 0.5 + (y * s + c.center_y) * f * a);
          const glm::dvec2 want(tan_l + src.x * (tan_r - tan_l), tan_t - src.y * (tan_t - tan_b));
          const glm::dvec2 q = (p - centre) * span;
          const double q2 = q.x * q.x + q.y * q.y;
          const glm::dvec2 msrc = centre + (p - centre) * (scale[ch] * (1 + q2 * (k1 + q2 * (k2 + q2 * k3))));
          const glm::dvec2 got(m_l + msrc.x * span.x, m_t - msrc.y * span.y);
          const double err = glm::length((got - want) / span * glm::dvec2(c.eye_width, c.eye_height));
          sum += err * err;
          ++n;
          worst[e] = std::max(worst[e], err);
        }
      }
    rms[e] = n ? std::sqrt(sum / n) : 1e9;
    if (!(rms[e] <= 0.5 && worst[e] <= 1.5)) {
      char b[160];
      std::snprintf(b, sizeof b, "%s eye shows directions off the config's by rms %.2f px, max %.2f px; ", side.c_str(), rms[e],
                    worst[e]);
      why += b;
    }
  }
  char b[200];
  std::snprintf(b, sizeof b, "size %.0fx%.0f ipd %.2f mm, distortion rms %.2f/%.2f px max %.2f/%.2f px ", num("/eye_width"),
                num("/eye_height"), num("/ipd_mm"), rms[0], rms[1], worst[0], worst[1]);
  return {why.empty(), b + why};
}

}  // namespace foveal::vmtest
