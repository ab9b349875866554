// The material extensions in the loader, without GL (docs/scenes.md, "Materials"): the
// factors and textures of KHR_materials_clearcoat, _sheen, _specular and _ior, the
// feature bits the compositor's shader variant is chosen by, KHR_materials_variants'
// mappings, and crafted values refused or clamped with the JSON path named.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "foveal/render/gltf_loader.hpp"
#include "gltf_test_models.hpp"
#include "test_support.hpp"

using namespace foveal;
using nlohmann::json;

namespace {

class Sink : public render::GltfSink {
 public:
  int add_texture(const render::GltfTexture&) override { return textures++; }
  int add_primitive(const std::vector<render::GltfVertex>&, const std::vector<std::uint32_t>&, int) override { return primitives++; }
  int textures = 0, primitives = 0;
};

// The quad with `materials` (its primitive uses the first) and a 1×1 PNG as image 0.
json with_materials(const json& materials) {
  json j = test::quad_model();
  j["materials"] = materials;
  j["meshes"][0]["primitives"][0]["material"] = 0;
  // A 1×1 PNG.
  j["images"] = {{{"uri", "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNkYPhfDwAChwGA60e6kgAAAABJRU5ErkJggg=="}}};
  j["textures"] = {{{"source", 0}}};
  return j;
}

Result<render::GltfScene> load(const json& j, Sink& sink) { return render::load_gltf_bytes(j.dump(), "crafted.gltf", ".", {}, sink); }

}  // namespace

TEST(GltfMaterials, PlainMaterialsHaveNoFeatures) {
  Sink sink;
  auto s = load(with_materials(json::array({{{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}}})), sink);
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->materials[0].features, 0u);
  EXPECT_FLOAT_EQ(s->materials[0].ior, 1.5f);
  EXPECT_FLOAT_EQ(s->materials[0].specular_factor, 1.0f);
}

TEST(GltfMaterials, ClearcoatSheenSpecularAndIorAreRead) {
  json m = {{"extensions",
             {{"KHR_materials_clearcoat",
               {{"clearcoatFactor", 0.75}, {"clearcoatRoughnessFactor", 0.25}, {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}},
              {"KHR_materials_sheen", {{"sheenColorFactor", {0.5, 0.25, 0.125}}, {"sheenRoughnessFactor", 0.6}, {"sheenColorTexture", {{"index", 0}}}}},
              {"KHR_materials_specular", {{"specularFactor", 0.4}, {"specularColorFactor", {2.0, 1.0, 0.5}}, {"specularTexture", {{"index", 0}}}}},
              {"KHR_materials_ior", {{"ior", 1.33}}}}}};
  json j = with_materials(json::array({m}));
  j["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_specular", "KHR_materials_ior"};
  Sink sink;
  auto s = load(j, sink);
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_TRUE(s->warnings.empty()) << s->warnings.front();
  const render::Material& mat = s->materials[0];
  EXPECT_EQ(mat.features, render::feature_clearcoat | render::feature_sheen | render::feature_specular);
  EXPECT_FLOAT_EQ(mat.clearcoat, 0.75f);
  EXPECT_FLOAT_EQ(mat.clearcoat_roughness, 0.25f);
  EXPECT_FLOAT_EQ(mat.clearcoat_normal_scale, 0.5f);
  EXPECT_GE(mat.texture(render::Material::clearcoat_normal_slot), 0);
  EXPECT_LT(mat.texture(render::Material::clearcoat_slot), 0);
  EXPECT_FLOAT_EQ(mat.sheen_color.g, 0.25f);
  EXPECT_FLOAT_EQ(mat.sheen_roughness, 0.6f);
  EXPECT_GE(mat.texture(render::Material::sheen_color_slot), 0);
  EXPECT_FLOAT_EQ(mat.specular_factor, 0.4f);
  EXPECT_FLOAT_EQ(mat.specular_color.r, 2.0f);  // the colour factor may exceed 1
  EXPECT_GE(mat.texture(render::Material::specular_slot), 0);
  EXPECT_FLOAT_EQ(mat.ior, 1.33f);
}

TEST(GltfMaterials, ZeroLayersAddNoFeature) {
  // A coat of factor 0 and a black sheen are no layer: the scene keeps the plain variant.
  json m = {{"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 0.0}, {"clearcoatTexture", {{"index", 0}}}}},
                            {"KHR_materials_sheen", json::object()}}}};
  Sink sink;
  auto s = load(with_materials(json::array({m})), sink);
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->materials[0].features, 0u);
}

TEST(GltfMaterials, OutOfRangeFactorsAreClampedWithTheirPath) {
  json m = {{"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 3.0}}}, {"KHR_materials_ior", {{"ior", 0.5}}}}}};
  Sink sink;
  auto s = load(with_materials(json::array({m})), sink);
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_FLOAT_EQ(s->materials[0].clearcoat, 1.0f);
  EXPECT_FLOAT_EQ(s->materials[0].ior, 1.0f);
  std::string all;
  for (const std::string& w : s->warnings) all += w + "\n";
  EXPECT_NE(all.find("materials[0].extensions.KHR_materials_clearcoat: clearcoatFactor"), std::string::npos) << all;
  EXPECT_NE(all.find("materials[0].extensions.KHR_materials_ior: ior"), std::string::npos) << all;
}

TEST(GltfMaterials, UnlitIgnoresLayers) {
  json m = {{"extensions", {{"KHR_materials_unlit", json::object()}, {"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}}}}};
  Sink sink;
  auto s = load(with_materials(json::array({m})), sink);
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->materials[0].features, 0u);
}

TEST(GltfMaterials, VariantsMapPrimitivesToMaterials) {
  json j = with_materials({{{"name", "red"}}, {{"name", "blue"}}, {{"name", "green"}}});
  j["extensionsUsed"] = {"KHR_materials_variants"};
  j["extensions"] = {{"KHR_materials_variants", {{"variants", {{{"name", "Blue"}}, {{"name", "Green"}}, {{"name", "Also blue"}}}}}}};
  j["meshes"][0]["primitives"][0]["extensions"] = {
      {"KHR_materials_variants", {{"mappings", {{{"material", 1}, {"variants", {0, 2}}}, {{"material", 2}, {"variants", {1}}}}}}}};
  Sink sink;
  auto s = load(j, sink);
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->variants.size(), 3u);
  EXPECT_EQ(s->variants[0].name, "Blue");
  ASSERT_EQ(s->variants[0].primitive_material.size(), 1u);
  EXPECT_EQ(s->variants[0].primitive_material[0], (std::pair<int, int>{0, 1}));
  EXPECT_EQ(s->variants[1].primitive_material[0], (std::pair<int, int>{0, 2}));
  EXPECT_EQ(s->variants[2].primitive_material[0], (std::pair<int, int>{0, 1}));
}

TEST(GltfMaterials, BadVariantMappingsAreRefusedWithTheirPath) {
  json j = with_materials({{{"name", "red"}}});
  j["extensions"] = {{"KHR_materials_variants", {{"variants", {{{"name", "A"}}}}}}};
  auto mapping = [&](const json& m) {
    json k = j;
    k["meshes"][0]["primitives"][0]["extensions"] = {{"KHR_materials_variants", {{"mappings", {m}}}}};
    Sink sink;
    return load(k, sink);
  };
  auto r = mapping({{"material", 5}, {"variants", {0}}});
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("meshes[0].primitives[0].extensions.KHR_materials_variants.mappings[0].material"), std::string::npos)
      << r.error().message;
  r = mapping({{"material", 0}, {"variants", {3}}});
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("mappings[0].variants[0]: not a variant index (1 variants)"), std::string::npos) << r.error().message;
  json k = j;
  k["extensions"]["KHR_materials_variants"]["variants"][0] = {{"label", "no name"}};
  Sink sink;
  r = load(k, sink);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("extensions.KHR_materials_variants.variants[0]: no name"), std::string::npos) << r.error().message;
}
