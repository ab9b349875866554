// The glTF JSON checked before tinygltf sees it. tinygltf 2.7 skips a value of the wrong
// type without a word (`"translation": ["a","b","c"]` becomes no translation,
// `"material": "x"` no material) and does not range-check most indices, so everything
// the renderer relies on is checked here, with the JSON path in the message.
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <set>

#include "gltf_internal.hpp"
#include "foveal/core/json_text.hpp"

namespace foveal::render::detail {

namespace {

using json = nlohmann::json;

std::string item(const std::string& array, std::size_t i) { return array + "[" + std::to_string(i) + "]"; }

std::string shown(const json& v) {
  std::string s = json_text(v);
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

class Checker {
 public:
  Checker(const json& root, std::string file) : root_(root), file_(std::move(file)) {}

  Status run() {
    if (!root_.is_object()) return fail("(root)", "a glTF file is a JSON object");
    for (const char* a : {"accessors", "bufferViews", "buffers", "images", "textures", "samplers", "materials", "meshes",
                          "nodes", "scenes", "cameras"})
      if (Status s = array_of_objects(a); !s) return s;
    if (Status s = index(root_, "scene", "scenes", "scene"); !s) return s;
    using Step = Status (Checker::*)() const;
    for (Step step : std::initializer_list<Step>{&Checker::buffers, &Checker::buffer_views, &Checker::accessors, &Checker::images,
                       &Checker::textures, &Checker::samplers, &Checker::materials, &Checker::meshes, &Checker::nodes,
                       &Checker::scenes})
      if (Status s = (this->*step)(); !s) return s;
    return {};
  }

 private:
  Error fail(const std::string& path, const std::string& what) const { return bad_input(file_ + ": " + path + ": " + what); }

  std::size_t count(const char* array) const {
    auto it = root_.find(array);
    return it != root_.end() && it->is_array() ? it->size() : 0;
  }
  const json& at(const char* array, std::size_t i) const { return root_[array][i]; }

  Status array_of_objects(const char* array) const {
    auto it = root_.find(array);
    if (it == root_.end()) return {};
    if (!it->is_array()) return fail(array, "must be an array, got " + shown(*it));
    for (std::size_t i = 0; i < it->size(); ++i)
      if (!(*it)[i].is_object()) return fail(item(array, i), "must be an object, got " + shown((*it)[i]));
    return {};
  }

  // An integer in [min, max] (absent: fine unless required).
  Status integer(const json& obj, const char* key, const std::string& path, bool required, std::uint64_t min = 0,
                 std::uint64_t max = UINT64_MAX) const {
    auto it = obj.find(key);
    if (it == obj.end()) return required ? Status(fail(path, "'" + std::string(key) + "' is missing")) : Status();
    const std::string where = path + "." + key;
    if (!it->is_number_integer()) return fail(where, "must be an integer, got " + shown(*it));
    const bool negative = !it->is_number_unsigned() && it->get<std::int64_t>() < 0;
    const std::uint64_t v = negative ? 0 : it->get<std::uint64_t>();
    if (negative || v < min || v > max)
      return fail(where, shown(*it) + " is out of range (" + std::to_string(min) +
                             (max == UINT64_MAX ? " or more" : ".." + std::to_string(max)) + ")");
    return {};
  }

  // An index into the top-level `array`.
  Status index_value(const json& v, const char* array, const std::string& path) const {
    if (!v.is_number_integer() || (!v.is_number_unsigned() && v.get<std::int64_t>() < 0))
      return fail(path, "must be an index into '" + std::string(array) + "' (an integer >= 0), got " + shown(v));
    const std::size_t n = count(array);
    if (v.get<std::uint64_t>() >= n)
      return fail(path, shown(v) + " is out of range (" + std::to_string(n) + " " + array + ")");
    return {};
  }

  Status index(const json& obj, const char* key, const char* array, const std::string& path, bool required = false) const {
    auto it = obj.find(key);
    if (it == obj.end()) return required ? Status(fail(path, "'" + std::string(key) + "' is missing")) : Status();
    return index_value(*it, array, path == key ? path : path + "." + key);
  }

  // A list of indices into `array`.
  Status index_list(const json& obj, const char* key, const char* array, const std::string& path) const {
    auto it = obj.find(key);
    if (it == obj.end()) return {};
    const std::string where = path + "." + key;
    if (!it->is_array()) return fail(where, "must be an array of indices, got " + shown(*it));
    for (std::size_t i = 0; i < it->size(); ++i)
      if (Status s = index_value((*it)[i], array, item(where, i)); !s) return s;
    return {};
  }

  Status number_value(const json& v, const std::string& path) const {
    if (!v.is_number()) return fail(path, "must be a number, got " + shown(v));
    const double d = v.get<double>();
    if (!std::isfinite(d) || std::fabs(d) > 3.0e38) return fail(path, shown(v) + " is out of range");
    return {};
  }

  Status number(const json& obj, const char* key, const std::string& path) const {
    auto it = obj.find(key);
    return it == obj.end() ? Status() : number_value(*it, path + "." + key);
  }

  // Exactly n numbers (a vector, quaternion or matrix).
  Status numbers(const json& obj, const char* key, std::size_t n, const std::string& path) const {
    auto it = obj.find(key);
    if (it == obj.end()) return {};
    const std::string where = path + "." + key;
    if (!it->is_array() || it->size() != n)
      return fail(where, "must be an array of " + std::to_string(n) + " numbers, got " + shown(*it));
    for (std::size_t i = 0; i < n; ++i)
      if (Status s = number_value((*it)[i], item(where, i)); !s) return s;
    return {};
  }

  Status one_of(const json& obj, const char* key, const std::set<std::string>& allowed, const std::string& path,
                bool required) const {
    auto it = obj.find(key);
    if (it == obj.end()) return required ? Status(fail(path, "'" + std::string(key) + "' is missing")) : Status();
    if (!it->is_string() || !allowed.count(it->get<std::string>())) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      return fail(path + "." + key, shown(*it) + " is not one of " + list);
    }
    return {};
  }

  Status buffers() const {
    for (std::size_t i = 0; i < count("buffers"); ++i) {
      const json& b = at("buffers", i);
      if (Status s = integer(b, "byteLength", item("buffers", i), true, 1); !s) return s;
      if (auto u = b.find("uri"); u != b.end() && !u->is_string()) return fail(item("buffers", i) + ".uri", "must be a string");
    }
    return {};
  }

  Status buffer_views() const {
    for (std::size_t i = 0; i < count("bufferViews"); ++i) {
      const json& v = at("bufferViews", i);
      const std::string path = item("bufferViews", i);
      if (Status s = index(v, "buffer", "buffers", path, true); !s) return s;
      if (Status s = integer(v, "byteOffset", path, false); !s) return s;
      if (Status s = integer(v, "byteLength", path, true, 1); !s) return s;
      if (Status s = integer(v, "byteStride", path, false, 4, 252); !s) return s;
      if (auto st = v.find("byteStride"); st != v.end() && st->get<std::int64_t>() % 4 != 0)
        return fail(path + ".byteStride", shown(*st) + " is not a multiple of 4");
      // Inside its buffer (tinygltf takes &data[byteOffset] of image views unchecked).
      const std::uint64_t offset = v.value("byteOffset", std::uint64_t{0}), length = v["byteLength"].get<std::uint64_t>();
      const std::uint64_t size = at("buffers", v["buffer"].get<std::size_t>())["byteLength"].get<std::uint64_t>();
      if (offset > size || length > size - offset)
        return fail(path, "byteOffset " + std::to_string(offset) + " + byteLength " + std::to_string(length) +
                              " is past the end of buffers[" + std::to_string(v["buffer"].get<std::size_t>()) + "] (" +
                              std::to_string(size) + " bytes)");
    }
    return {};
  }

  Status accessors() const {
    static const std::set<std::int64_t> kComponentTypes = {5120, 5121, 5122, 5123, 5125, 5126};
    for (std::size_t i = 0; i < count("accessors"); ++i) {
      const json& a = at("accessors", i);
      const std::string path = item("accessors", i);
      if (Status s = index(a, "bufferView", "bufferViews", path); !s) return s;
      if (Status s = integer(a, "byteOffset", path, false); !s) return s;
      if (Status s = integer(a, "componentType", path, true, 5120, 5126); !s) return s;
      if (!kComponentTypes.count(a["componentType"].get<std::int64_t>()))
        return fail(path + ".componentType", shown(a["componentType"]) + " is not a glTF component type");
      if (Status s = integer(a, "count", path, true, 1); !s) return s;
      if (Status s = one_of(a, "type", {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}, path, true); !s) return s;
      if (auto n = a.find("normalized"); n != a.end() && !n->is_boolean())
        return fail(path + ".normalized", "must be true or false, got " + shown(*n));
    }
    return {};
  }

  Status images() const {
    for (std::size_t i = 0; i < count("images"); ++i) {
      const json& im = at("images", i);
      if (Status s = index(im, "bufferView", "bufferViews", item("images", i)); !s) return s;
      if (auto u = im.find("uri"); u != im.end() && !u->is_string()) return fail(item("images", i) + ".uri", "must be a string");
    }
    return {};
  }

  Status textures() const {
    for (std::size_t i = 0; i < count("textures"); ++i) {
      const json& t = at("textures", i);
      if (Status s = index(t, "source", "images", item("textures", i)); !s) return s;
      if (Status s = index(t, "sampler", "samplers", item("textures", i)); !s) return s;
    }
    return {};
  }

  Status samplers() const {
    for (std::size_t i = 0; i < count("samplers"); ++i)
      for (const char* key : {"wrapS", "wrapT"}) {
        const json& sm = at("samplers", i);
        auto w = sm.find(key);
        if (w == sm.end()) continue;
        if (!w->is_number_integer() || (*w != 10497 && *w != 33071 && *w != 33648))
          return fail(item("samplers", i) + "." + key, shown(*w) + " is not a glTF wrap mode (10497, 33071, 33648)");
      }
    return {};
  }

  Status texture_info(const json& obj, const char* key, const std::string& path) const {
    auto it = obj.find(key);
    if (it == obj.end()) return {};
    const std::string where = path + "." + key;
    if (!it->is_object()) return fail(where, "must be an object, got " + shown(*it));
    if (Status s = index(*it, "index", "textures", where, true); !s) return s;
    // tinygltf narrows texCoord to int: 4294967297 became 1.
    if (Status s = integer(*it, "texCoord", where, false, 0, INT32_MAX); !s) return s;
    if (Status s = number(*it, "scale", where); !s) return s;
    if (Status s = number(*it, "strength", where); !s) return s;
    return texture_transform(*it, where);
  }

  // KHR_texture_transform: the loader read members of the wrong type as absent.
  Status texture_transform(const json& info, const std::string& path) const {
    auto ext = info.find("extensions");
    if (ext == info.end() || !ext->is_object()) return {};
    auto t = ext->find("KHR_texture_transform");
    if (t == ext->end()) return {};
    const std::string where = path + ".extensions.KHR_texture_transform";
    if (!t->is_object()) return fail(where, "must be an object, got " + shown(*t));
    if (Status s = numbers(*t, "offset", 2, where); !s) return s;
    if (Status s = numbers(*t, "scale", 2, where); !s) return s;
    if (Status s = number(*t, "rotation", where); !s) return s;
    return integer(*t, "texCoord", where, false, 0, INT32_MAX);
  }

  Status materials() const {
    for (std::size_t i = 0; i < count("materials"); ++i) {
      const json& m = at("materials", i);
      const std::string path = item("materials", i);
      if (auto pbr = m.find("pbrMetallicRoughness"); pbr != m.end()) {
        const std::string p = path + ".pbrMetallicRoughness";
        if (!pbr->is_object()) return fail(p, "must be an object, got " + shown(*pbr));
        if (Status s = numbers(*pbr, "baseColorFactor", 4, p); !s) return s;
        if (Status s = number(*pbr, "metallicFactor", p); !s) return s;
        if (Status s = number(*pbr, "roughnessFactor", p); !s) return s;
        if (Status s = texture_info(*pbr, "baseColorTexture", p); !s) return s;
        if (Status s = texture_info(*pbr, "metallicRoughnessTexture", p); !s) return s;
      }
      for (const char* t : {"normalTexture", "occlusionTexture", "emissiveTexture"})
        if (Status s = texture_info(m, t, path); !s) return s;
      if (auto ext = m.find("extensions"); ext != m.end() && ext->is_object())
        if (auto sg = ext->find("KHR_materials_pbrSpecularGlossiness"); sg != ext->end() && sg->is_object()) {
          const std::string p = path + ".extensions.KHR_materials_pbrSpecularGlossiness";
          for (const char* t : {"diffuseTexture", "specularGlossinessTexture"})
            if (Status s = texture_info(*sg, t, p); !s) return s;
        }
      if (Status s = numbers(m, "emissiveFactor", 3, path); !s) return s;
      if (Status s = number(m, "alphaCutoff", path); !s) return s;
      if (Status s = one_of(m, "alphaMode", {"OPAQUE", "MASK", "BLEND"}, path, false); !s) return s;
      if (auto d = m.find("doubleSided"); d != m.end() && !d->is_boolean())
        return fail(path + ".doubleSided", "must be true or false, got " + shown(*d));
    }
    return {};
  }

  Status meshes() const {
    for (std::size_t i = 0; i < count("meshes"); ++i) {
      const json& m = at("meshes", i);
      const std::string path = item("meshes", i);
      auto prims = m.find("primitives");
      if (prims == m.end() || !prims->is_array() || prims->empty())
        return fail(path + ".primitives", "must be a non-empty array");
      for (std::size_t k = 0; k < prims->size(); ++k) {
        const json& p = (*prims)[k];
        const std::string pp = item(path + ".primitives", k);
        if (!p.is_object()) return fail(pp, "must be an object, got " + shown(p));
        auto attrs = p.find("attributes");
        if (attrs == p.end() || !attrs->is_object()) return fail(pp + ".attributes", "must be an object");
        for (auto a = attrs->begin(); a != attrs->end(); ++a)
          if (Status s = index_value(a.value(), "accessors", pp + ".attributes." + a.key()); !s) return s;
        if (Status s = index(p, "indices", "accessors", pp); !s) return s;
        if (Status s = index(p, "material", "materials", pp); !s) return s;
        if (Status s = integer(p, "mode", pp, false, 0, 6); !s) return s;
      }
    }
    return {};
  }

  // The hierarchy must be a forest (glTF 2.0, 5.25): with one parent per node and the
  // depth limit in the builder, walking it visits each node once.
  Status nodes() const {
    parent_.assign(count("nodes"), SIZE_MAX);
    for (std::size_t i = 0; i < count("nodes"); ++i) {
      const json& n = at("nodes", i);
      const std::string path = item("nodes", i);
      if (Status s = index(n, "mesh", "meshes", path); !s) return s;
      if (Status s = index(n, "camera", "cameras", path); !s) return s;
      if (Status s = index_list(n, "children", "nodes", path); !s) return s;
      if (Status s = numbers(n, "matrix", 16, path); !s) return s;
      if (Status s = numbers(n, "translation", 3, path); !s) return s;
      if (Status s = numbers(n, "rotation", 4, path); !s) return s;
      if (Status s = numbers(n, "scale", 3, path); !s) return s;
      if (auto c = n.find("children"); c != n.end())
        for (std::size_t k = 0; k < c->size(); ++k) {
          const std::size_t child = (*c)[k].get<std::size_t>();
          if (child == i) return fail(item(path + ".children", k), "a node cannot be its own child");
          if (parent_[child] != SIZE_MAX)
            return fail(item(path + ".children", k), item("nodes", child) + " already has a parent (" +
                                                         item("nodes", parent_[child]) + "); the hierarchy must be a forest");
          parent_[child] = i;
        }
    }
    return {};
  }

  Status scenes() const {
    for (std::size_t i = 0; i < count("scenes"); ++i) {
      const json& s = at("scenes", i);
      const std::string path = item("scenes", i);
      if (Status st = index_list(s, "nodes", "nodes", path); !st) return st;
      auto list = s.find("nodes");
      if (list == s.end()) continue;
      std::set<std::size_t> seen;
      for (std::size_t k = 0; k < list->size(); ++k) {
        const std::size_t n = (*list)[k].get<std::size_t>();
        if (parent_[n] != SIZE_MAX)
          return fail(item(path + ".nodes", k), item("nodes", n) + " is a child of " + item("nodes", parent_[n]) +
                                                    ", not a root node");
        if (!seen.insert(n).second) return fail(item(path + ".nodes", k), item("nodes", n) + " is listed twice");
      }
    }
    return {};
  }

  const json& root_;
  std::string file_;
  mutable std::vector<std::size_t> parent_;  // filled by nodes(), read by scenes()
};

}  // namespace

Status check_gltf_json(const nlohmann::json& root, const std::string& file) { return Checker(root, file).run(); }

}  // namespace foveal::render::detail
