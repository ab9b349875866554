// The glTF loader without GL: real models load, crafted ones are refused with the file
// and the JSON path named, before anything is allocated from their counts.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <cstring>

#include "foveal/render/gltf_loader.hpp"
#include "foveal/render/view_file.hpp"
#include "gltf_test_models.hpp"
#include "test_support.hpp"

using namespace foveal;
using nlohmann::json;

namespace {

class CountingSink : public render::GltfSink {
 public:
  int add_texture(const render::GltfTexture& t) override {
    pixels += static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height);
    return textures++;
  }
  int add_primitive(const std::vector<render::GltfVertex>& v, const std::vector<std::uint32_t>& idx, int) override {
    vertices += v.size();
    for (std::uint32_t i : idx) EXPECT_LT(i, v.size());
    EXPECT_EQ(idx.size() % 3, 0u);
    return primitives++;
  }
  int textures = 0, primitives = 0;
  std::size_t vertices = 0, pixels = 0;
};

Result<render::GltfScene> load_json(const json& j, render::GltfLimits limits = {}) {
  CountingSink sink;
  return render::load_gltf_bytes(j.dump(), "crafted.gltf", ".", limits, sink);
}

// Expects a bad-input error naming crafted.gltf and containing `what`.
void expect_refused(const Result<render::GltfScene>& r, const std::string& what, ErrorKind kind = ErrorKind::bad_input) {
  ASSERT_FALSE(r) << "loaded, expected: " << what;
  EXPECT_EQ(r.error().kind, kind) << r.error().message;
  EXPECT_NE(r.error().message.find("crafted.gltf"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find(what), std::string::npos) << r.error().message;
}

long peak_rss_kb() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

}  // namespace

TEST(GltfLoader, TheQuadAndTheBundledScenesLoad) {
  auto q = load_json(test::quad_model());
  ASSERT_TRUE(q) << q.error().message;
  EXPECT_EQ(q->triangles, 2u);
  EXPECT_EQ(q->draws.size(), 1u);
  for (const auto& [file, triangles] : {std::pair{"data/scenes/WaterBottle/WaterBottle.gltf", 4510u},
                                        std::pair{"data/scenes/Dungeon/dungeon_simplified.gltf", 42606u}}) {
    CountingSink sink;
    auto s = render::load_gltf(test::source_path(file), {}, sink);
    ASSERT_TRUE(s) << s.error().message;
    EXPECT_EQ(s->triangles, triangles) << file;
    EXPECT_GT(sink.textures, 0) << file;
  }
}

TEST(GltfLoader, DeepJsonIsRefusedBeforeTinygltfParsesIt) {
  json j = test::quad_model();
  const std::string text = j.dump();
  // 100,000-deep extras: tinygltf's recursive value parser overflowed the stack on it.
  std::string deep = text.substr(0, text.size() - 1) + ",\"extras\":" + test::nested_arrays(100000) + "}";
  CountingSink sink;
  auto r = render::load_gltf_bytes(deep, "crafted.gltf", ".", {}, sink);
  expect_refused(r, "JSON nested deeper than 64 levels");
  // The same in a .glb's JSON chunk.
  while (deep.size() % 4) deep += ' ';
  std::string glb = "glTF";
  auto le32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  glb += le32(2) + le32(static_cast<std::uint32_t>(20 + deep.size())) + le32(static_cast<std::uint32_t>(deep.size())) +
         le32(0x4E4F534Au) + deep;
  r = render::load_gltf_bytes(glb, "crafted.gltf", ".", {}, sink);
  expect_refused(r, "JSON nested deeper than 64 levels");
  render::GltfLimits small;
  small.max_json_bytes = 100;
  expect_refused(load_json(test::quad_model(), small), "more than the 100 bytes accepted");
}

TEST(GltfLoader, HugeCountsAreRefusedBeforeAnyAllocation) {
  const long before = peak_rss_kb();
  for (std::uint64_t count : {4000000000ull, 100000000ull, 5ull}) {
    json j = test::quad_model();
    j["accessors"][0]["count"] = count;
    expect_refused(load_json(j), "accessors[0]: count " + std::to_string(count) + " × stride 12 from byteOffset 0 reads past the end of bufferViews[0] (48 bytes)");
  }
  // Without a buffer view an accessor is all zeros: bounded too.
  json j = test::quad_model();
  j["accessors"][0].erase("bufferView");
  j["accessors"][0]["count"] = 100000000;
  expect_refused(load_json(j), "accessors[0].count: 100000000 elements without a buffer view");
  EXPECT_LT(peak_rss_kb() - before, 100 * 1024) << "the loader allocated for a count it should have refused";
}

TEST(GltfLoader, OffsetsAndStridesCannotWrapOrLeaveTheBuffer) {
  json j = test::quad_model();
  j["accessors"][0]["byteOffset"] = 18446744073709551600ull;  // offset + stride * n wraps in 64 bits
  expect_refused(load_json(j), "accessors[0]: count 4");
  j = test::quad_model();
  j["bufferViews"][0]["byteOffset"] = 18446744073709551600ull;
  expect_refused(load_json(j), "bufferViews[0]: byteOffset");
  j = test::quad_model();
  j["bufferViews"][1]["byteLength"] = 4000;
  expect_refused(load_json(j), "is past the end of buffers[0] (60 bytes)");
  j = test::quad_model();
  j["bufferViews"][0]["byteStride"] = 8;
  expect_refused(load_json(j), "bufferViews[0].byteStride: 8 is less than the 12-byte elements of accessors[0]");
  j = test::quad_model();
  j["bufferViews"][0]["byteStride"] = 13;
  expect_refused(load_json(j), "bufferViews[0].byteStride: 13 is not a multiple of 4");
  j["bufferViews"][0]["byteStride"] = 256;
  expect_refused(load_json(j), "bufferViews[0].byteStride: 256 is out of range (4..252)");
}

TEST(GltfLoader, WhatTheRendererReliesOnIsValidatedWithTheJsonPath) {
  struct Case {
    const char* what;
    void (*edit)(json&);
    const char* message;
    ErrorKind kind = ErrorKind::bad_input;
  };
  const Case cases[] = {
      {"material out of range", [](json& j) { j["meshes"][0]["primitives"][0]["material"] = 42; },
       "meshes[0].primitives[0].material: 42 is out of range (0 materials)"},
      {"material of the wrong type", [](json& j) { j["meshes"][0]["primitives"][0]["material"] = "x"; },
       "meshes[0].primitives[0].material: must be an index"},
      {"matrix of 3", [](json& j) { j["nodes"][0]["matrix"] = {1, 2, 3}; }, "nodes[0].matrix: must be an array of 16 numbers"},
      {"translation of strings", [](json& j) { j["nodes"][0]["translation"] = {"a", "b", "c"}; },
       "nodes[0].translation[0]: must be a number"},
      {"infinite scale", [](json& j) { j["nodes"][0]["scale"] = {1e300, 1, 1}; }, "nodes[0].scale[0]: 1e+300 is out of range"},
      {"5 indices", [](json& j) { j["accessors"][1]["count"] = 5; },
       "meshes[0].primitives[0].indices: count 5 is not a multiple of 3"},
      {"4 vertices, no indices", [](json& j) { j["meshes"][0]["primitives"][0].erase("indices"); },
       "meshes[0].primitives[0].attributes.POSITION: count 4 is not a multiple of 3"},
      {"POSITION as UNSIGNED_INT", [](json& j) { j["accessors"][0]["componentType"] = 5125; },
       "accessors[0]: component type UNSIGNED_INT is not one the renderer reads for meshes[0].primitives[0].attributes.POSITION"},
      {"POSITION as VEC2", [](json& j) { j["accessors"][0]["type"] = "VEC2"; }, "accessors[0]: type VEC2 is not VEC3"},
      {"indices as FLOAT", [](json& j) { j["accessors"][1]["componentType"] = 5126; },
       "accessors[1]: component type FLOAT is not one the renderer reads for meshes[0].primitives[0].indices"},
      {"indices as VEC3", [](json& j) { j["accessors"][1]["type"] = "VEC3"; }, "accessors[1]: type VEC3 is not SCALAR"},
      {"component type INT (not glTF)", [](json& j) { j["accessors"][0]["componentType"] = 5124; },
       "accessors[0].componentType: 5124 is not a glTF component type"},
      {"unknown accessor type", [](json& j) { j["accessors"][0]["type"] = "VEC5"; }, "accessors[0].type: \"VEC5\" is not one of"},
      {"attribute index out of range", [](json& j) { j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 9; },
       "meshes[0].primitives[0].attributes.NORMAL: 9 is out of range (2 accessors)"},
      {"mesh out of range", [](json& j) { j["nodes"][0]["mesh"] = 3; }, "nodes[0].mesh: 3 is out of range (1 meshes)"},
      {"child of two parents",
       [](json& j) {
         j["nodes"] = {{{"mesh", 0}, {"children", {2}}}, {{"children", {2}}}, json::object()};
         j["scenes"][0]["nodes"] = {0, 1};
       },
       "nodes[1].children[0]: nodes[2] already has a parent (nodes[0])"},
      {"own child", [](json& j) { j["nodes"][0]["children"] = {0}; }, "nodes[0].children[0]: a node cannot be its own child"},
      {"scene lists a child", [](json& j) { j["nodes"] = {{{"mesh", 0}, {"children", {1}}}, json::object()}; j["scenes"][0]["nodes"] = {0, 1}; },
       "scenes[0].nodes[1]: nodes[1] is a child of nodes[0], not a root node"},
      {"negative buffer view", [](json& j) { j["accessors"][0]["bufferView"] = -1; }, "accessors[0].bufferView: must be an index"},
      {"sparse count above the accessor's",
       [](json& j) { j["accessors"][0]["sparse"] = {{"count", 5}, {"indices", {{"bufferView", 1}, {"componentType", 5123}}}, {"values", {{"bufferView", 0}}}}; },
       "accessor 0 (sparse): sparse count 5 outside 1..4"},
      {"texture of a missing image", [](json& j) { j["textures"] = {{{"source", 0}}}; }, "textures[0].source: 0 is out of range (0 images)"},
      {"not an object", [](json& j) { j = json::array(); }, "(root): a glTF file is a JSON object"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    json j = test::quad_model();
    c.edit(j);
    expect_refused(load_json(j), c.message, c.kind);
  }
  json j = test::quad_model(test::quad_buffer({0, 1, 7, 0, 2, 3}));
  expect_refused(load_json(j), "meshes[0].primitives[0].indices: index 2 is 7, not below the vertex count 4");
}

TEST(GltfLoader, ImageDimensionsAreCheckedBeforeDecoding) {
  auto with_image = [](const std::string& png) {
    json j = test::quad_model();
    j["images"] = {{{"uri", test::data_uri(png, "image/png")}, {"name", "claims"}}};
    j["textures"] = {{{"source", 0}}};
    j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    j["meshes"][0]["primitives"][0]["material"] = 0;
    return j;
  };
  const long before = peak_rss_kb();
  expect_refused(load_json(with_image(test::png_header(100000, 100000))),
                 "images[0] (claims): 100000×100000 is larger than the texture size limit 16384 (GL_MAX_TEXTURE_SIZE)");
  expect_refused(load_json(with_image(test::png_header(40000, 2))), "40000×2 is larger than the texture size limit 16384");
  expect_refused(load_json(with_image(test::png_header(16000, 16000))),
                 "16000×16000 needs 976 MiB decoded, more than the 256 MiB per image accepted");
  render::GltfLimits gl;
  gl.max_texture_size = 8192;  // as the compositor passes its GL_MAX_TEXTURE_SIZE
  expect_refused(load_json(with_image(test::png_header(8193, 1)), gl), "8193×1 is larger than the texture size limit 8192");
  // A chunk longer than the bytes there are (stb_image would size its buffer from it
  // first: 2 GiB for this one; fuzz_gltf, tests/fuzz/regressions/gltf/).
  std::string idat = test::png_header(4, 4);
  idat.insert(33, std::string{0x40, 0, 0, 0} + "IDAT");
  expect_refused(load_json(with_image(idat)), "images[0] (claims): PNG chunk at byte 33 claims 1073741824 bytes, past the end of the image (53 bytes)");
  EXPECT_LT(peak_rss_kb() - before, 100 * 1024);
  expect_refused(load_json(with_image("not a png")), "images[0] (claims): not an image stb_image can decode");
  // An image in a buffer view that runs past its buffer (tinygltf 2.7 reads it unchecked).
  json j = test::quad_model();
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 4000}});
  j["images"] = {{{"bufferView", 2}, {"mimeType", "image/png"}}};
  expect_refused(load_json(j), "bufferViews[2]: byteOffset 48 + byteLength 4000 is past the end of buffers[0] (60 bytes)");
  j["bufferViews"][2]["byteLength"] = 12;  // inside, but not an image
  expect_refused(load_json(j), "images[0]: not an image stb_image can decode");
}

TEST(GltfLoader, FilesThatAreNotRegularAreRefused) {
  test::TempDir d;
  ASSERT_EQ(::mkfifo(d.path("model.gltf").c_str(), 0600), 0);
  CountingSink sink;
  auto r = render::load_gltf(d.path("model.gltf"), {}, sink);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("is a FIFO"), std::string::npos) << r.error().message;
  // An external buffer that is a FIFO.
  json j = test::quad_model();
  j["buffers"][0]["uri"] = "quad.bin";
  ASSERT_EQ(::mkfifo(d.path("quad.bin").c_str(), 0600), 0);
  test::write_file(d.path("quad2.gltf"), j.dump());
  r = render::load_gltf(d.path("quad2.gltf"), {}, sink);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("quad.bin: file referenced by"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("is a FIFO"), std::string::npos) << r.error().message;
}

TEST(GltfLoader, ReferencedFilesAreLookedUpBesideTheModelOnly) {
  test::TempDir model_dir, cwd;
  json j = test::quad_model();
  j["buffers"][0]["uri"] = "quad.bin";
  test::write_file(model_dir.path("quad.gltf"), j.dump());
  test::write_file(cwd.path("quad.bin"), test::quad_buffer());  // tinygltf would also look in "."
  const auto before = std::filesystem::current_path();
  std::filesystem::current_path(cwd.path());
  CountingSink sink;
  auto r = render::load_gltf(model_dir.path("quad.gltf"), {}, sink);
  std::filesystem::current_path(before);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("File not found : quad.bin"), std::string::npos) << r.error().message;
  test::write_file(model_dir.path("quad.bin"), test::quad_buffer());
  r = render::load_gltf(model_dir.path("quad.gltf"), {}, sink);
  EXPECT_TRUE(r) << r.error().message;
}

TEST(ViewFile, DeepOrBrokenViewFilesAreRefusedNamingTheFile) {
  test::TempDir d;
  test::write_file(d.path("a.view.json"), "{\"eye\": " + test::nested_arrays(500000) + "}");  // 1 MB, under the size limit
  auto v = render::read_view_file(d.path("a.view.json"));
  ASSERT_FALSE(v);
  EXPECT_NE(v.error().message.find("a.view.json: JSON nested deeper than 64 levels"), std::string::npos) << v.error().message;
  test::write_file(d.path("b.view.json"), R"({"eye": [0, 0, 1e39], "target": [0, 0, 0]})");
  v = render::read_view_file(d.path("b.view.json"));
  ASSERT_FALSE(v);
  EXPECT_NE(v.error().message.find("'eye' is out of range"), std::string::npos) << v.error().message;
  test::write_file(d.path("c.view.json"), R"({"eye": [0, 0, 1], "target": [0, 0, 0], "units_per_meter": 2})");
  v = render::read_view_file(d.path("c.view.json"));
  ASSERT_TRUE(v) << v.error().message;
  EXPECT_FLOAT_EQ(v->units_per_meter, 2.0f);
}
