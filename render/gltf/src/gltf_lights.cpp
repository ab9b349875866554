#include "gltf_lights.hpp"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "foveal/core/json_text.hpp"

namespace foveal::render::detail {

namespace {

using json = nlohmann::json;

const char* const kExt = "KHR_lights_punctual";

std::string item(const std::string& array, std::size_t i) { return array + "[" + std::to_string(i) + "]"; }

std::string shown(const json& v) {
  std::string s = json_text(v);
  return s.size() > 40 ? s.substr(0, 37) + "..." : s;
}

// The extension object under `obj.extensions`, or null when absent.
const json* extension(const json& obj) {
  auto ext = obj.find("extensions");
  if (ext == obj.end() || !ext->is_object()) return nullptr;
  auto it = ext->find(kExt);
  return it == ext->end() ? nullptr : &*it;
}

class LightChecker {
 public:
  LightChecker(const json& root, std::string file, std::vector<std::string>& warnings)
      : root_(root), file_(std::move(file)), warnings_(warnings) {}

  Status run() {
    std::size_t lights = 0;
    if (const json* ext = extension(root_)) {
      const std::string path = std::string("extensions.") + kExt;
      if (!ext->is_object()) return fail(path, "must be an object, got " + shown(*ext));
      auto list = ext->find("lights");
      if (list == ext->end() || !list->is_array()) return fail(path + ".lights", "must be an array of lights");
      for (std::size_t i = 0; i < list->size(); ++i)
        if (Status s = light((*list)[i], item(path + ".lights", i)); !s) return s;
      lights = list->size();
    }
    auto nodes = root_.find("nodes");
    if (nodes == root_.end() || !nodes->is_array()) return {};
    for (std::size_t i = 0; i < nodes->size(); ++i) {
      const json* ext = (*nodes)[i].is_object() ? extension((*nodes)[i]) : nullptr;
      if (!ext) continue;
      const std::string path = item("nodes", i) + ".extensions." + kExt;
      if (!ext->is_object()) return fail(path, "must be an object, got " + shown(*ext));
      auto l = ext->find("light");
      if (l == ext->end()) return fail(path, "'light' is missing");
      if (!l->is_number_integer() || (!l->is_number_unsigned() && l->get<std::int64_t>() < 0))
        return fail(path + ".light", "must be an index into the extension's lights (an integer >= 0), got " + shown(*l));
      if (l->get<std::uint64_t>() >= lights)
        return fail(path + ".light", shown(*l) + " is out of range (" + std::to_string(lights) + " lights)");
    }
    return {};
  }

 private:
  Error fail(const std::string& path, const std::string& what) const { return bad_input(file_ + ": " + path + ": " + what); }

  // A finite number at obj[key] into `out` (absent: `out` unchanged, `present` false).
  Status number(const json& obj, const char* key, const std::string& path, double& out, bool* present = nullptr) const {
    auto it = obj.find(key);
    if (present) *present = it != obj.end();
    if (it == obj.end()) return {};
    if (!it->is_number() || !std::isfinite(it->get<double>()) || std::fabs(it->get<double>()) > 3.0e38)
      return fail(path + "." + key, "must be a finite number, got " + shown(*it));
    out = it->get<double>();
    return {};
  }

  Status light(const json& l, const std::string& path) const {
    if (!l.is_object()) return fail(path, "must be an object, got " + shown(l));
    auto type = l.find("type");
    if (type == l.end()) return fail(path, "'type' is missing");
    if (!type->is_string() || (*type != "directional" && *type != "point" && *type != "spot"))
      return fail(path + ".type", shown(*type) + " is not one of directional, point, spot");
    if (auto c = l.find("color"); c != l.end()) {
      if (!c->is_array() || c->size() != 3) return fail(path + ".color", "must be an array of 3 numbers, got " + shown(*c));
      for (std::size_t k = 0; k < 3; ++k) {
        if (!(*c)[k].is_number() || !std::isfinite((*c)[k].get<double>()))
          return fail(item(path + ".color", k), "must be a finite number, got " + shown((*c)[k]));
        const double v = (*c)[k].get<double>();
        if (v < 0) return fail(item(path + ".color", k), shown((*c)[k]) + " is negative (a colour is in [0, 1])");
        if (v > 1)
          warnings_.push_back(file_ + ": " + item(path + ".color", k) + ": " + shown((*c)[k]) +
                              " is above 1 (a colour is in [0, 1]); used as given");
      }
    }
    double intensity = 1, range = 0;
    bool has_range = false;
    if (Status s = number(l, "intensity", path, intensity); !s) return s;
    if (intensity < 0) return fail(path + ".intensity", shown(l["intensity"]) + " is negative");
    // Past this the shader's float arithmetic overflows (3e38 lit the surface black).
    if (intensity > 1e9)
      return fail(path + ".intensity", shown(l["intensity"]) + " is beyond 1e9 (candela or lux; the sun is about 1e5 lux)");
    if (Status s = number(l, "range", path, range, &has_range); !s) return s;
    if (has_range && !(range > 0)) return fail(path + ".range", shown(l["range"]) + " is not greater than 0");
    auto spot = l.find("spot");
    if (*type != "spot") return {};
    if (spot == l.end() || !spot->is_object()) return fail(path + ".spot", "a spot light needs a 'spot' object");
    double inner = 0, outer = std::numbers::pi / 4;
    if (Status s = number(*spot, "innerConeAngle", path + ".spot", inner); !s) return s;
    if (Status s = number(*spot, "outerConeAngle", path + ".spot", outer); !s) return s;
    if (inner < 0) return fail(path + ".spot.innerConeAngle", std::to_string(inner) + " is negative");
    if (outer > std::numbers::pi / 2)
      return fail(path + ".spot.outerConeAngle", std::to_string(outer) + " is more than pi/2");
    if (!(inner < outer))
      return fail(path + ".spot.innerConeAngle",
                  std::to_string(inner) + " is not less than outerConeAngle " + std::to_string(outer));
    return {};
  }

  const json& root_;
  std::string file_;
  std::vector<std::string>& warnings_;
};

}  // namespace

Status check_gltf_lights(const nlohmann::json& root, const std::string& file, std::vector<std::string>& warnings) {
  return LightChecker(root, file, warnings).run();
}

Result<std::vector<PunctualLight>> node_light(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world,
                                              const std::string& file, const std::string& path) {
  std::vector<PunctualLight> out;
  auto ext = node.extensions.find(kExt);
  if (ext == node.extensions.end() || !ext->second.Has("light")) return out;
  const int index = ext->second.Get("light").GetNumberAsInt();
  if (index < 0 || static_cast<std::size_t>(index) >= model.lights.size())
    return bad_input(file + ": " + path + ".extensions.KHR_lights_punctual.light: out of range");
  const tinygltf::Light& l = model.lights[static_cast<std::size_t>(index)];
  PunctualLight p;
  p.index = index;
  p.type = l.type == "directional" ? PunctualLight::Type::directional
                                   : l.type == "spot" ? PunctualLight::Type::spot : PunctualLight::Type::point;
  if (l.color.size() == 3)
    p.color = glm::vec3(static_cast<float>(l.color[0]), static_cast<float>(l.color[1]), static_cast<float>(l.color[2]));
  p.intensity = static_cast<float>(l.intensity);
  // tinygltf reads an absent range as 0; the checks refused a range <= 0 that was given.
  p.range = p.type == PunctualLight::Type::directional ? 0.0f : static_cast<float>(l.range);
  p.inner_cone = static_cast<float>(l.spot.innerConeAngle);
  p.outer_cone = static_cast<float>(l.spot.outerConeAngle);
  p.position = glm::vec3(world[3]);
  const glm::vec3 d = -glm::vec3(world[2]);
  const float len = glm::length(d);
  if (!(len > 0) || !std::isfinite(len)) {
    if (p.type != PunctualLight::Type::point)
      return bad_input(file + ": " + path + ": the transform of its light (KHR_lights_punctual.lights[" + std::to_string(index) +
                       "]) has no −Z direction");
  } else {
    p.direction = d / len;
  }
  out.push_back(p);
  return out;
}

}  // namespace foveal::render::detail
