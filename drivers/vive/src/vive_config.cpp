#include "foveal/drivers/vive/vive_config.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "foveal/core/json_file.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/core/shown_text.hpp"

namespace foveal::vive {
namespace {

using nlohmann::json;

/// Walks the JSON with the key path for messages.
class Node {
 public:
  Node(const json& j, std::string path) : j_(j), path_(std::move(path)) {}
  const json& get() const { return j_; }
  const std::string& path() const { return path_; }
  bool has(const char* key) const { return j_.is_object() && j_.contains(key); }
  Result<Node> at(const char* key) const {
    if (!j_.is_object()) return err("expected an object");
    if (!j_.contains(key)) return bad_input(path_ + (path_.empty() ? "" : ".") + key + ": missing");
    return Node(j_.at(key), path_ + (path_.empty() ? "" : ".") + key);
  }
  Result<Node> at(std::size_t i) const {
    if (!j_.is_array() || j_.size() <= i) return err("expected an array of at least " + std::to_string(i + 1));
    return Node(j_.at(i), path_ + "[" + std::to_string(i) + "]");
  }
  Result<double> number() const {
    if (!j_.is_number()) return err("expected a number");
    const double d = j_.get<double>();
    if (!std::isfinite(d) || std::fabs(d) > 1e6) return err("the number is out of range");
    return d;
  }
  Result<int> pixels() const {
    if (!j_.is_number_integer() || j_.get<std::int64_t>() < 1 || j_.get<std::int64_t>() > 16384)
      return err("expected a whole number of pixels in 1..16384");
    return static_cast<int>(j_.get<std::int64_t>());
  }
  Result<glm::vec3> vec3() const {
    if (!j_.is_array() || j_.size() != 3) return err("expected an array of 3 numbers");
    glm::vec3 v(0.0f);
    for (int k = 0; k < 3; ++k) {
      auto n = Node(j_.at(static_cast<std::size_t>(k)), path_).number();
      if (!n) return n.error();
      v[k] = static_cast<float>(*n);
    }
    return v;
  }
  Error err(const std::string& what) const { return bad_input(path_ + ": " + what); }

 private:
  const json& j_;
  std::string path_;
};

#define FOVEAL_TRY(var, expr)           \
  auto var##_r = (expr);                \
  if (!var##_r) return var##_r.error(); \
  auto var = std::move(*var##_r)

Result<ChannelDistortion> parse_channel(const Node& d) {
  ChannelDistortion c;
  if (d.has("type")) {
    const json& t = d.get().at("type");
    if (!t.is_string() || (t != "DISTORT_DPOLY3" && t != "DISTORT_DPOLY3_SCALED"))
      return bad_input(d.path() + ".type: " + shown_text(json_text(t)) + " is not DISTORT_DPOLY3 (the only model read)");
  }
  FOVEAL_TRY(cx, d.at("center_x"));
  FOVEAL_TRY(cxv, cx.number());
  FOVEAL_TRY(cy, d.at("center_y"));
  FOVEAL_TRY(cyv, cy.number());
  c.center_x = cxv, c.center_y = cyv;
  FOVEAL_TRY(k, d.at("coeffs"));
  if (!k.get().is_array() || k.get().size() < 3) return k.err("expected an array of at least 3 numbers");
  for (std::size_t i = 0; i < 4 && i < k.get().size(); ++i) {
    FOVEAL_TRY(ki, k.at(i));
    FOVEAL_TRY(kv, ki.number());
    c.coeffs[i] = kv;
  }
  return c;
}

Result<EyeOptics> parse_eye(const Node& e) {
  EyeOptics o;
  FOVEAL_TRY(in, e.at("intrinsics"));
  const json& m = in.get();
  bool ok = m.is_array() && m.size() == 3;
  for (std::size_t r = 0; ok && r < 3; ++r) {
    ok = m[r].is_array() && m[r].size() == 3;
    for (std::size_t c = 0; ok && c < 3; ++c) ok = m[r][c].is_number() && std::isfinite(m[r][c].get<double>());
  }
  if (!ok) return in.err("expected a 3x3 array of numbers");
  o.fx = m[0][0].get<double>(), o.cx = m[0][2].get<double>();
  o.fy = m[1][1].get<double>(), o.cy = m[1][2].get<double>();
  if (!(o.fx > 0.05 && o.fx < 100 && o.fy > 0.05 && o.fy < 100)) return in.err("focal lengths must be in (0.05, 100)");
  if (e.has("grow_for_undistort")) {
    FOVEAL_TRY(g, e.at("grow_for_undistort"));
    FOVEAL_TRY(gv, g.number());
    if (!(gv >= 0 && gv < 10)) return g.err("must be in [0, 10)");
    o.grow_for_undistort = gv;
  }
  if (e.has("undistort_r2_cutoff")) {
    FOVEAL_TRY(c, e.at("undistort_r2_cutoff"));
    FOVEAL_TRY(cv, c.number());
    if (!(cv > 0)) return c.err("must be > 0");
    o.undistort_r2_cutoff = cv;
  }
  FOVEAL_TRY(green_node, e.at("distortion"));
  FOVEAL_TRY(green, parse_channel(green_node));
  o.rgb = {green, green, green};
  const char* names[3] = {"distortion_red", nullptr, "distortion_blue"};
  for (std::size_t c : {std::size_t{0}, std::size_t{2}}) {
    if (!e.has(names[c])) continue;
    FOVEAL_TRY(n, e.at(names[c]));
    FOVEAL_TRY(ch, parse_channel(n));
    o.rgb[c] = ch;
  }
  return o;
}

Result<glm::vec3> optional_vec3(const Node& parent, const char* key, glm::vec3 fallback) {
  if (!parent.has(key)) return fallback;
  FOVEAL_TRY(n, parent.at(key));
  return n.vec3();
}

Status check_label(const std::string& text, const std::string& where) {
  constexpr std::size_t kMaxLabelBytes = 64;
  if (text.size() > kMaxLabelBytes)
    return bad_input(where + ": " + std::to_string(text.size()) + " bytes (\"" + shown_text(text) + "\"); at most " +
                     std::to_string(kMaxLabelBytes));
  for (char ch : text)
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f)
      return bad_input(where + ": \"" + shown_text(text) + "\" contains a control character");
  return {};
}

}  // namespace

Result<Config> parse_config(const std::string& text, const std::string& where) {
  // Size and depth limits before nlohmann parses it: a 400,000-deep value recursed
  // in dump() until SIGSEGV.
  auto parsed = parse_json(text, where);
  if (!parsed) return parsed.error();
  const json& j = *parsed;
  if (!j.is_object()) return bad_input(where + ": expected a JSON object");
  const Node root(j, where + ":");
  Config c;
  const char* model_key = j.contains("model_number") ? "model_number" : "model_name";
  if (!j.contains(model_key) || !j.at(model_key).is_string())
    return bad_input(where + ": model_number: missing (neither model_number nor model_name is a string)");
  c.model_number = j.at(model_key).get<std::string>();
  // Both end up in the display model's name and source: short printable text only.
  if (Status s = check_label(c.model_number, where + ": " + model_key); !s) return s.error();
  c.variant = c.model_number.find("Pro") != std::string::npos || c.model_number.find("PRO") != std::string::npos
                  ? Variant::vive_pro
                  : Variant::vive;
  if (j.contains("device_serial_number") && j["device_serial_number"].is_string())
    c.serial = j["device_serial_number"].get<std::string>();
  if (Status s = check_label(c.serial, where + ": device_serial_number"); !s) return s.error();

  FOVEAL_TRY(device, root.at("device"));
  FOVEAL_TRY(w, device.at("eye_target_width_in_pixels"));
  FOVEAL_TRY(wv, w.pixels());
  FOVEAL_TRY(h, device.at("eye_target_height_in_pixels"));
  FOVEAL_TRY(hv, h.pixels());
  c.eye_width = wv, c.eye_height = hv;
  if (device.has("physical_aspect_x_over_y")) {
    FOVEAL_TRY(a, device.at("physical_aspect_x_over_y"));
    FOVEAL_TRY(av, a.number());
    if (!(av > 0.1 && av < 10)) return a.err("must be in (0.1, 10)");
    c.aspect_x_over_y = av;
  }
  if (root.has("lens_separation")) {
    FOVEAL_TRY(l, root.at("lens_separation"));
    FOVEAL_TRY(lv, l.number());
    if (!(lv > 0.02 && lv < 0.1)) return l.err("must be in (0.02, 0.1) metres");
    c.ipd_m = lv;
  } else if (root.has("ipd")) {
    FOVEAL_TRY(ipd, root.at("ipd"));
    FOVEAL_TRY(mm, ipd.at("default_mm"));
    FOVEAL_TRY(mmv, mm.number());
    if (!(mmv > 20 && mmv < 100)) return mm.err("must be in (20, 100) mm");
    c.ipd_m = mmv / 1000.0;
  }
  FOVEAL_TRY(eyes, root.at("tracking_to_eye_transform"));
  for (std::size_t e = 0; e < 2; ++e) {
    FOVEAL_TRY(eye, eyes.at(e));
    FOVEAL_TRY(optics, parse_eye(eye));
    c.eyes[e] = optics;
  }
  // The IMU calibration: under "imu" on the Vive Pro, at the top on the original Vive.
  const Node imu = root.has("imu") ? *root.at("imu") : root;
  FOVEAL_TRY(ab, optional_vec3(imu, "acc_bias", c.acc_bias));
  FOVEAL_TRY(as, optional_vec3(imu, "acc_scale", c.acc_scale));
  FOVEAL_TRY(gb, optional_vec3(imu, "gyro_bias", c.gyro_bias));
  FOVEAL_TRY(gs, optional_vec3(imu, "gyro_scale", c.gyro_scale));
  c.acc_bias = ab, c.acc_scale = as, c.gyro_bias = gb, c.gyro_scale = gs;
  return c;
}

#undef FOVEAL_TRY

ImuSample imu_to_sample(const ImuRawSample& s, const Config& c, const ImuRange& range) {
  const float ga = static_cast<float>(range.gyro_rad_s / 32768.0), aa = static_cast<float>(range.accel_m_s2 / 32768.0);
  glm::vec3 g, a;
  for (int k = 0; k < 3; ++k) {
    g[k] = ga * c.gyro_scale[k] * s.gyro[static_cast<std::size_t>(k)] - c.gyro_bias[k];
    a[k] = aa * c.acc_scale[k] * s.accel[static_cast<std::size_t>(k)] - c.acc_bias[k];
  }
  // The sensor's axes against the head's differ by model (Monado's mapping).
  const glm::vec3 flip = c.variant == Variant::vive ? glm::vec3(1, -1, -1) : glm::vec3(-1, 1, -1);
  ImuSample out;
  out.gyro_rad_s = g * flip;
  out.accel_m_s2 = a * flip;
  return out;
}

}  // namespace foveal::vive
